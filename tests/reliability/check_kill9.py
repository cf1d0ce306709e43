#!/usr/bin/python3
"""Crash safety of a real run (docs/file-format.md: the file stays readable, with every
record written so far, if the process is killed at any moment): `rollsim run` is killed
with SIGKILL at random moments; the file left behind must open with netCDF4, say
status "running", and hold every record up to the last completed output interval, each
complete (tests/reliability/rs_check.py: check_records).

"Completed" is taken from the progress bar: rollsim draws it on stderr when stderr is a
terminal, after each record is written, so stderr is a pseudo-terminal here and the last
"t = T" drawn before the kill says that records 0 .. T/dt are in the file. The file may
hold one record more (written, bar not drawn yet), never fewer. (T is drawn with 4 digits:
beyond 9999 records it only gives the count to within ten.)

Usage: check_kill9.py ROLLSIM CASE.yaml WORKDIR [TRIALS]
CASE is cases/default.yaml made long (rolled_distance = 40 m, from rest, or from the
steady state in every other trial). A quarter of the trials kill within 50 ms of the
start (case loading, model set-up, file creation), the others 0.05-0.8 s in (records).
The seed is printed; set RS_KILL_SEED to repeat a run.
"""
import os
import random
import re
import signal
import subprocess
import sys
import threading
import time

import netCDF4

sys.dont_write_bytecode = True
from rs_check import DT, MU, PIN, check_records, prepare_dir  # noqa: E402

# From rest the first records take many IDA steps each (the traction builds up); from the
# steady state each takes a few, so records follow each other every ~1 ms and kills land
# inside record writes more often.
# 40 m of rolling (133 334 records) cannot end before the kill on any machine.
FROM_REST = ["--set", "simulation.rolled_distance=40000"] + PIN
FROM_STEADY = FROM_REST + ["--set", "simulation.initial_state=steady"]


def records_shown(text):
    """The bar draws t with %.4g: the range of record counts k+1 (records 0 .. k) whose
    time k*dt prints as text (one k up to k = 9999, up to ten beyond)."""
    k0 = round(float(text) / DT)
    span = k0 // 500 + 5
    ks = [k for k in range(max(0, k0 - span), k0 + span + 1) if "%.4g" % (k * DT) == text]
    assert ks, f"progress bar time {text!r} is no output time"
    return min(ks) + 1, max(ks) + 1


def read_all(fd, sink):
    while True:
        try:
            data = os.read(fd, 65536)
        except OSError:  # EIO: the terminal's other side is closed
            break
        if not data:
            break
        sink.extend(data)


def trial(rollsim, case, out, n, delay, sets):
    path = os.path.join(out, f"kill{n:02d}.nc")
    master, slave = os.openpty()
    proc = subprocess.Popen([rollsim, "run", case, "-o", path] + sets,
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    bar = bytearray()
    reader = threading.Thread(target=read_all, args=(master, bar))
    reader.start()
    time.sleep(delay)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    reader.join(timeout=10)
    os.close(master)
    where = f"trial {n} (kill after {delay * 1000:.0f} ms)"
    assert proc.returncode == -signal.SIGKILL, \
        f"{where}: rollsim ended with {proc.returncode} before the kill: {bytes(bar)[-300:]!r}"

    drawn = re.findall(rb"t = ([0-9.eE+-]+) / ", bytes(bar))
    done, done_hi = records_shown(drawn[-1].decode()) if drawn else (0, 0)
    if not os.path.exists(path):
        assert done == 0, f"{where}: {path} missing, but the bar showed {done} records"
        return delay, done, None
    with netCDF4.Dataset(path) as ds:
        assert ds.data_model == "NETCDF3_64BIT_OFFSET", f"{where}: {ds.data_model}"
        assert ds.status == "running", f"{where}: status {ds.status!r}"
        nrec = check_records(ds, DT, MU, f"{where}: {path}")
    assert done <= nrec <= done_hi + 1, \
        f"{where}: {nrec} records in the file, the progress bar showed {done}"
    assert not os.path.exists(path + ".part"), f"{where}: {path}.part left next to {path}"
    return delay, done, nrec


def main():
    rollsim, case, workdir = sys.argv[1:4]
    trials = int(sys.argv[4]) if len(sys.argv) > 4 else 24
    seed = int(os.environ.get("RS_KILL_SEED", random.SystemRandom().randrange(1 << 30)))
    print(f"seed {seed} (RS_KILL_SEED), {trials} trials")
    rng = random.Random(seed)
    out = prepare_dir(workdir)
    started = time.monotonic()
    no_file = 0
    most = 0
    for n in range(trials):
        delay = rng.uniform(0.0, 0.05) if n % 4 == 0 else rng.uniform(0.05, 0.8)
        sets = FROM_STEADY if n % 2 else FROM_REST
        delay, done, nrec = trial(rollsim, case, out, n, delay, sets)
        if nrec is None:
            no_file += 1
            print(f"  trial {n:2d}: killed after {delay * 1000:4.0f} ms: no file yet (start-up)")
        else:
            most = max(most, nrec)
            print(f"  trial {n:2d}: killed after {delay * 1000:4.0f} ms: {nrec:4d} complete "
                  f"records (progress bar: {done}){' from steady' if n % 2 else ''}")
            os.remove(os.path.join(out, f"kill{n:02d}.nc"))
    print(f"ok: {trials} kills in {time.monotonic() - started:.1f} s; {no_file} before the file "
          f"existed, the others left a valid file with up to {most} records")


if __name__ == "__main__":
    main()
