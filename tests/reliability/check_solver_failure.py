#!/usr/bin/python3
"""A solver failure mid-run (tests/reliability/solver_fail.yaml: IDA_TOO_MUCH_WORK just
after t = 0.5 ms): exit code 3, a message with the simulated time and the reason, and a
netCDF file that keeps every record up to the failure, with status "failed: <why>".

Usage: check_solver_failure.py ROLLSIM CASE.yaml WORKDIR
"""
import math
import os
import re
import sys

import netCDF4

sys.dont_write_bytecode = True
from rs_check import check_records, prepare_dir, run, summary_records  # noqa: E402

DT = 1.0e-5   # solver_fail.yaml simulation.output_interval, s
MU = 0.3
MAX_STEPS = 30


def main():
    rollsim, case, workdir = sys.argv[1:4]
    out = prepare_dir(workdir)
    path = os.path.join(out, "failed.nc")
    code, stdout, stderr = run(rollsim, ["run", case, "-o", path, "--quiet"])
    print(stderr + stdout)
    assert code == 3, f"exit code {code}, want 3 (solver failure)"

    m = re.search(r"failed at t = ([0-9.eE+-]+) s", stderr)
    assert m, f"the message does not give the simulated time: {stderr}"
    t_fail = float(m.group(1))
    assert "max_steps" in stderr and "IDA_TOO_MUCH_WORK" in stderr, \
        f"the message does not give the reason: {stderr}"
    assert 4.9e-4 < t_fail < 1.0e-3, f"failed at t = {t_fail} s, expected just after 0.5 ms"
    # the failed interval's steps are counted too (at least max_steps of them)
    steps = re.search(r"IDA steps (\d+)", stdout)
    assert steps and int(steps.group(1)) >= MAX_STEPS, f"summary step count: {stdout}"

    with netCDF4.Dataset(path) as ds:
        status = ds.status
        assert status.startswith("failed: "), f"status {status!r}"
        assert "max_steps" in status and f"t = {m.group(1)} s" in status, \
            f"status does not say why and when: {status!r}"
        nrec = check_records(ds, DT, MU, path)
    # every output time before the failure is in the file, none after it
    want = math.floor(t_fail / DT + 1e-9) + 1
    assert nrec == want, f"{nrec} records, want {want} (t = 0 .. {(want - 1) * DT:g} s)"
    assert summary_records(stdout) == nrec, \
        f"the summary says {summary_records(stdout)} records, the file has {nrec}"
    print(f"ok: exit 3 at t = {t_fail:g} s, {nrec} complete records, status {status!r}")


if __name__ == "__main__":
    main()
