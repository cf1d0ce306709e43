#!/usr/bin/python3
"""Crash safety of a sweep file with its points written in batches (README "Sweep files"):
`rollsim sweep` on a 2000-point steady creep curve is killed with SIGKILL at random
moments; the file left behind must open with netCDF4, say status "running", and hold
every point the promise covers, each complete.

The promise: a batch is written when a point is given 0.5 s or more after the last write,
so of two points given 0.5 s apart the earlier is in the file once the later has been
given. The progress bar (drawn on stderr when it is a terminal, after each point is given
to the file) says when each point was given; it is read through a pseudo-terminal and
time-stamped as it arrives. A point k is required in the file when a later point was drawn
0.8 s or more after it (0.3 s for the reader's lag). The points of the curve come in order
(an elastic 2D line), so the file holds points 0 .. m-1 (converged, finite forces) and
nothing beyond, with m at least the required count and at most the last count drawn + 1.

Usage: check_sweep_kill9.py ROLLSIM CASE.yaml WORKDIR [TRIALS]
CASE is bench/cases/creep_curve.yaml; kills 1-3 s after the start. The seed is printed;
set RS_KILL_SEED to repeat a run.
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
import numpy as np

POINTS = 2000
SETS = ["--set", "grid.cells=841",
        "--set", f"sweep.rolling.creepage={{linspace: [0.0, -0.02, {POINTS}]}}"]
LAG = 0.3  # s: how late the reader may time-stamp a bar


def read_all(fd, sink):
    """(monotonic time, bytes) of every read from the terminal."""
    while True:
        try:
            data = os.read(fd, 65536)
        except OSError:  # EIO: the terminal's other side is closed
            break
        if not data:
            break
        sink.append((time.monotonic(), data))


def trial(rollsim, case, out, n, delay):
    path = os.path.join(out, f"sweep_kill{n:02d}.nc")
    if os.path.exists(path):
        os.remove(path)
    master, slave = os.openpty()
    proc = subprocess.Popen([rollsim, "sweep", case, "-o", path] + SETS,
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    chunks = []
    reader = threading.Thread(target=read_all, args=(master, chunks))
    reader.start()
    time.sleep(delay)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    reader.join(timeout=10)
    os.close(master)
    where = f"trial {n} (kill after {delay * 1000:.0f} ms)"
    assert proc.returncode == -signal.SIGKILL, \
        f"{where}: rollsim ended with {proc.returncode} before the kill"
    drawn = []  # (time read, points given)
    for t, data in chunks:
        for count in re.findall(rb"sweep: ([0-9]+)/", data):
            drawn.append((t, int(count)))
    last = drawn[-1][1] if drawn else 0
    required = 0
    for t_k, k in drawn:
        if any(t_j >= t_k + 0.5 + LAG for t_j, _ in drawn):
            required = max(required, k)
    if not os.path.exists(path):
        assert last == 0, f"{where}: {path} missing, but the bar showed {last} points"
        return 0, 0, 0
    with netCDF4.Dataset(path) as ds:
        ds.set_auto_mask(False)
        assert ds.status == "running", f"{where}: status {ds.status!r}"
        conv = np.asarray(ds["converged"][:])
        fx = np.asarray(ds["Fx"][:])
    written = np.flatnonzero(conv == 1)
    m = len(written)
    assert np.array_equal(written, np.arange(m)), \
        f"{where}: the points in the file are not 0 .. {m - 1}: {written[:20]}..."
    assert np.all(np.isfinite(fx[:m])) and np.all(np.isnan(fx[m:])), \
        f"{where}: F_x of the points written not finite, or of the others not NaN"
    assert required <= m <= last + 1, \
        f"{where}: {m} points in the file; {required} required, the bar showed {last}"
    os.remove(path)
    return m, required, last


def main():
    rollsim, case, workdir = sys.argv[1:4]
    trials = int(sys.argv[4]) if len(sys.argv) > 4 else 4
    seed = int(os.environ.get("RS_KILL_SEED", random.SystemRandom().randrange(1 << 30)))
    print(f"seed {seed} (RS_KILL_SEED), {trials} trials")
    rng = random.Random(seed)
    os.makedirs(workdir, exist_ok=True)
    for n in range(trials):
        delay = rng.uniform(1.0, 3.0)
        m, required, last = trial(rollsim, case, workdir, n, delay)
        print(f"  trial {n}: killed after {delay * 1000:4.0f} ms: {m} points in the file, "
              f"{required} required, {last} given")
    print("ok")


if __name__ == "__main__":
    main()
