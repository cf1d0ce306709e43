#!/usr/bin/python3
"""Crash safety of the netCDF output: kill the writer with SIGKILL at random moments and
check that every file left behind opens with netCDF4 and holds at least the records the
writer reported as completed before the kill, each with the right values.

Usage: check_output_crash.py WRITER WORKDIR [TRIALS]

WRITER is tests/test_output_crash_writer.c built (see its header for the values). Each
trial starts one writer process and kills it after a random delay of 0-100 ms, measured
from the start of the process (kills during start-up and file creation) or, every other
trial, from the moment the file exists (kills during records). Every third trial writes
without pausing between records, so kills land inside write() calls more often.
The seed is printed; set RS_CRASH_SEED to repeat a run.
"""
import os
import random
import signal
import subprocess
import sys
import time

import netCDF4

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from check_output import check_values  # noqa: E402 (the writer's values, shared)

NX = 200


def check_file(path, reported):
    """Open the file left by a killed writer; return the number of records it holds."""
    with netCDF4.Dataset(path) as ds:
        assert ds.data_model == "NETCDF3_64BIT_OFFSET", f"{path}: {ds.data_model}"
        assert ds.Conventions == "CF-1.10"
        status = ds.status
        assert status.startswith("running"), f"{path}: status {status!r}"
        nrec = len(ds.dimensions["time"])
        # the writer prints after the sync: at most one record more than reported
        assert reported <= nrec <= reported + 1, \
            f"{path}: {nrec} records, writer reported {reported}"
        check_values(ds, nrec, path)
        return nrec


def run_trial(writer, path, rng, trial):
    for stale in (path, path + ".part"):
        if os.path.exists(stale):
            os.remove(stale)
    from_creation = trial % 2 == 1
    pause_ms = "0" if trial % 3 == 2 else "2"
    delay = rng.uniform(0.0, 0.1)
    proc = subprocess.Popen([writer, path, "1000000", pause_ms, str(NX)],
                            stdout=subprocess.PIPE)
    lines = []
    if from_creation:
        first = proc.stdout.readline()
        assert first.strip() == b"0", f"writer did not start: {first!r}"
        lines.append(first)
    time.sleep(delay)
    proc.send_signal(signal.SIGKILL)
    rest, _ = proc.communicate()
    assert proc.returncode == -signal.SIGKILL, \
        f"writer ended with {proc.returncode} before the kill"
    lines += rest.split()
    reported = int(lines[-1]) if lines else None
    if reported is None:
        # killed before the file existed: nothing promised, but a file there must be valid
        nrec = check_file(path, 0) if os.path.exists(path) else None
    else:
        assert os.path.exists(path), f"{path} missing after the writer reported {reported}"
        nrec = check_file(path, reported)
    return delay, from_creation, pause_ms, reported, nrec


def main():
    writer, workdir = sys.argv[1], sys.argv[2]
    trials = int(sys.argv[3]) if len(sys.argv) > 3 else 24
    seed = int(os.environ.get("RS_CRASH_SEED", random.SystemRandom().randrange(1 << 30)))
    rng = random.Random(seed)
    os.makedirs(workdir, exist_ok=True)
    print(f"seed {seed}, {trials} trials")
    failures = 0
    mid_run = kept = extra = 0
    started = time.monotonic()
    for trial in range(trials):
        path = os.path.join(workdir, f"crash{trial}.nc")
        try:
            delay, from_creation, pause_ms, reported, nrec = run_trial(writer, path, rng, trial)
        except AssertionError as err:
            failures += 1
            print(f"trial {trial}: FAILED: {err}")
            continue
        print(f"trial {trial}: kill after {1e3 * delay:5.1f} ms from "
              f"{'creation' if from_creation else 'start   '} (pause {pause_ms} ms): "
              f"reported {reported}, file holds {nrec}")
        if reported is not None and reported > 0:
            mid_run += 1
        if nrec is not None:
            kept += nrec
            if reported is not None and nrec > reported:
                extra += 1
        for done in (path, path + ".part"):  # keep only the files of failed trials
            if os.path.exists(done):
                os.remove(done)
    print(f"{trials} trials in {time.monotonic() - started:.1f} s: {mid_run} killed while "
          f"writing records, {kept} records kept in total, {extra} files held one record "
          f"more than reported (killed between sync and print), {failures} failed")
    if mid_run < trials // 4:
        print("too few kills landed while records were being written")
        failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
