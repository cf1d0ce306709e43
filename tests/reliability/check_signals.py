#!/usr/bin/python3
"""SIGINT and SIGTERM during a long run: exit code 4, a message with the simulated time,
status "interrupted", and every record up to that time kept, complete.

Usage: check_signals.py ROLLSIM CASE.yaml WORKDIR
CASE is cases/default.yaml, made to last minutes with simulation.rolled_distance = 40 m;
the signal comes 0.2-0.6 s after the output file appears. Set RS_SIGNAL_SEED to repeat.
Then a run stuck in one long output interval: a second SIGINT must end it at once.
"""
import math
import os
import random
import re
import signal
import subprocess
import sys
import time

import netCDF4

sys.dont_write_bytecode = True
from rs_check import DT, MU, PIN, check_records, prepare_dir, summary_records  # noqa: E402


def wait_for(path, proc, timeout=20.0):
    end = time.monotonic() + timeout
    while not os.path.exists(path):
        assert proc.poll() is None, f"rollsim ended ({proc.returncode}) before creating {path}"
        assert time.monotonic() < end, f"{path} not created within {timeout} s"
        time.sleep(0.005)


def wait_for_records(path, proc, n, timeout=30.0):
    """Wait until the file holds n records (the run is loaded or slow on a busy machine)."""
    end = time.monotonic() + timeout
    while True:
        assert proc.poll() is None, f"rollsim ended ({proc.returncode}) before writing {n} records"
        assert time.monotonic() < end, f"{path}: {n} records not written within {timeout} s"
        try:
            with netCDF4.Dataset(path) as ds:
                if len(ds.dimensions["time"]) >= n:
                    return
        except OSError:
            pass
        time.sleep(0.01)


def trial(rollsim, case, out, sig, delay):
    path = os.path.join(out, f"{sig.name}.nc")
    proc = subprocess.Popen([rollsim, "run", case, "-o", path, "--quiet",
                             "--set", "simulation.rolled_distance=40000"] + PIN,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        wait_for(path, proc)
        wait_for_records(path, proc, 2)
        time.sleep(delay)
        assert proc.poll() is None, f"rollsim ended ({proc.returncode}) before the signal"
        proc.send_signal(sig)
        stdout, stderr = proc.communicate(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    stdout, stderr = stdout.decode(), stderr.decode()
    where = f"{sig.name} after {delay:.3f} s"
    assert proc.returncode == 4, f"{where}: exit code {proc.returncode}, want 4\n{stderr}"
    m = re.search(r"interrupted at t = ([0-9.eE+-]+) s", stderr)
    assert m, f"{where}: message does not give the simulated time: {stderr}"
    t_stop = float(m.group(1))
    with netCDF4.Dataset(path) as ds:
        assert ds.status == "interrupted", f"{where}: status {ds.status!r}"
        nrec = check_records(ds, DT, MU, f"{where}: {path}")
    # records at every output time up to the stop (the stop may fall inside an interval)
    want = math.floor(t_stop / DT + 1e-6) + 1
    assert nrec == want and nrec >= 2, \
        f"{where}: {nrec} records, want {want} (stopped at t = {t_stop} s)"
    assert summary_records(stdout) == nrec, \
        f"{where}: the summary says {summary_records(stdout)} records, the file has {nrec}"
    print(f"ok: {where}: exit 4 at t = {t_stop:g} s, {nrec} complete records; "
          f"{stderr.strip()}")


def second_signal(rollsim, case, out):
    """One output interval of many seconds of solver work (a fast-oscillating creepage and
    output_interval = 0.5 s): the first SIGINT must stop the run inside the interval with
    exit 4, and the file must stay valid (the record at t = 0, complete)."""
    path = os.path.join(out, "second_signal.nc")
    proc = subprocess.Popen([rollsim, "run", case, "-o", path, "--quiet",
                             "--set", "simulation.rolled_distance=40000"] + PIN + [
                             "--set", "simulation.output_interval=0.5",
                             "--set", "rolling.creepage={sine: {mean: -2.4e-4, amplitude: 2e-4,"
                                      " frequency: 2000.0, phase: 0.0}}"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        wait_for(path, proc)
        time.sleep(0.2)
        proc.send_signal(signal.SIGINT)
        # The integrator checks the flag in every residual evaluation: the run stops
        # within the interval, long before its end (0.5 s of simulated time).
        proc.wait(timeout=2.0)
        assert proc.returncode == 4, f"first SIGINT: exit {proc.returncode}, want 4"
        want_status = "interrupted"
        how = "the first SIGINT stopped the run inside the output interval (exit 4)"
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    with netCDF4.Dataset(path) as ds:
        assert ds.status == want_status, f"second SIGINT: status {ds.status!r}"
        nrec = len(ds.dimensions["time"])
        assert nrec >= 1 and ds["time"][0] == 0.0 and (ds["n_exterior"][:] > 0).all(), \
            f"second SIGINT: {nrec} records, t = {ds['time'][:]}"
    print(f"ok: long output interval: {how}; file valid, status {want_status!r}, {nrec} record(s)")


def main():
    rollsim, case, workdir = sys.argv[1:4]
    seed = int(os.environ.get("RS_SIGNAL_SEED", random.SystemRandom().randrange(1 << 30)))
    print(f"seed {seed} (RS_SIGNAL_SEED)")
    rng = random.Random(seed)
    out = prepare_dir(workdir)
    for sig in (signal.SIGINT, signal.SIGTERM):
        trial(rollsim, case, out, sig, rng.uniform(0.2, 0.6))
    second_signal(rollsim, case, out)


if __name__ == "__main__":
    main()
