#!/usr/bin/env python3
"""A full disk, imitated by a file-size limit (RLIMIT_FSIZE with SIGXFSZ ignored: a write
beyond the limit fails with EFBIG, as one on a full disk fails with ENOSPC).

  check_full_disk.py sweep ROLLSIM CASE DIR [--set ...]
      The sweep file is allocated whole when it is created, so a full disk stops the sweep
      before its first point: exit 1, a message naming the file, no summary, no file (and an
      existing file of that name untouched, no .part left behind).
  check_full_disk.py run ROLLSIM CASE DIR
      A transient whose disk fills after some records: exit 1, the records before the
      failure readable, status "failed: ... File too large"; `--restart F --append` with
      room again finishes it, and its end agrees with an uninterrupted run's to 1e-4 of
      max |F_x| or three times the run's relative tolerance (solver_rtol), whichever is
      larger (the continuation restarts IDA at first order from the stored record, so it
      differs by a few of its error tolerances, not by the fill).
  check_full_disk.py fit ROLLSIM CASE DIR
      A fit whose first file write fails: exit 1, a message naming the file, no file.
"""
import os
import resource
import shutil
import signal
import subprocess
import sys

import netCDF4
import numpy as np


def limited(kbytes):
    def setup():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (kbytes * 1024, resource.RLIM_INFINITY))
    return setup


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run(cmd, kbytes=None):
    p = subprocess.run(cmd, capture_output=True, text=True,
                       preexec_fn=limited(kbytes) if kbytes else None)
    return p


def expect_output_error(p, path, what):
    if p.returncode != 1:
        fail(f"{what}: exit {p.returncode}, expected 1 (output error)\n{p.stdout}{p.stderr}")
    if path not in p.stderr or "File too large" not in p.stderr:
        fail(f"{what}: the message does not name {path} and the cause:\n{p.stderr}")


def check_sweep(binary, case, sets):
    out = "sweep.nc"
    p = run([binary, "sweep", case, "-o", out, "--quiet"] + sets)
    if p.returncode != 0:
        fail("the sweep without a limit failed:\n" + p.stderr)
    size = os.path.getsize(out)
    shutil.copy(out, "old.nc")
    with open("old.nc", "rb") as f:
        old = f.read()
    # a limit of a tenth of the file: the layout cannot be written
    p = run([binary, "sweep", case, "-o", "old.nc", "--quiet"] + sets, max(1, size // 10240))
    expect_output_error(p, "old.nc", "sweep")
    if "output:" in p.stdout or "points solved" in p.stdout:
        fail("a sweep that wrote no file prints a summary:\n" + p.stdout)
    with open("old.nc", "rb") as f:
        if f.read() != old:
            fail("the existing file was changed by a sweep that could not write")
    leftovers = [f for f in os.listdir(".") if f.endswith(".part") or f.endswith("~")]
    if leftovers:
        fail(f"files left behind: {leftovers}")
    p = run([binary, "sweep", case, "-o", "new.nc", "--quiet"] + sets, max(1, size // 10240))
    expect_output_error(p, "new.nc", "sweep")
    if os.path.exists("new.nc") or os.path.exists("new.nc.part"):
        fail("a sweep that could not write its layout left a file")
    print(f"sweep: file of {size} bytes, limit {max(1, size // 10240)} KiB: exit 1, no file, "
          "the old one untouched")


def check_run(binary, case):
    p = run([binary, "run", case, "-o", "whole.nc", "--quiet"])
    if p.returncode != 0:
        fail("the run without a limit failed:\n" + p.stderr)
    size = os.path.getsize("whole.nc")
    kb = size // 4096  # a quarter of the file: some records fit, most do not
    p = run([binary, "run", case, "-o", "full.nc", "--quiet"], kb)
    expect_output_error(p, "full.nc", "run")
    with netCDF4.Dataset("full.nc") as d:
        status = d.getncattr("status")
        n = len(d["time"])
        t = d["time"][:]
        fx = d["Fx"][:]
    with netCDF4.Dataset("whole.nc") as d:
        n_whole = len(d["time"])
        fx_whole = d["Fx"][:]
        tol = max(1e-4, 3.0 * float(d.getncattr("solver_rtol")))
    if not status.startswith("failed:") or "File too large" not in status:
        fail(f"status after the failed write: {status!r}")
    if not 0 < n < n_whole or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(fx)):
        fail(f"records kept: {n} of {n_whole}, times increasing and forces finite expected")
    p = run([binary, "run", case, "--restart", "full.nc", "--append", "--quiet"])
    if p.returncode != 0:
        fail("the continuation with room again failed:\n" + p.stdout + p.stderr)
    with netCDF4.Dataset("full.nc") as d:
        status = d.getncattr("status")
        fx_cont = d["Fx"][:]
    if status != "complete" or len(fx_cont) != n_whole:
        fail(f"continued file: status {status!r}, {len(fx_cont)} of {n_whole} records")
    dev = float(np.max(np.abs(fx_cont - fx_whole)) / np.max(np.abs(fx_whole)))
    if dev > tol:
        fail(f"continued run differs from the uninterrupted one by {dev:.3g} of max |F_x| "
             f"(tolerance {tol:.3g})")
    print(f"run: {n} of {n_whole} records kept at a limit of {kb} KiB, status failed; "
          f"continued with --append: largest F_x difference {dev:.2g} of max |F_x|")


def check_fit(binary, case):
    p = run([binary, "fit", case, "-o", "fit.nc", "--quiet"], 1)
    expect_output_error(p, "fit.nc", "fit")
    if os.path.exists("fit.nc") or os.path.exists("fit.nc.part"):
        fail("a fit that could not write left a file")
    print("fit: exit 1, no file")


def main():
    mode, binary, case, work = sys.argv[1:5]
    sets = sys.argv[5:]
    binary, case = os.path.abspath(binary), os.path.abspath(case)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    {"sweep": lambda: check_sweep(binary, case, sets),
     "run": lambda: check_run(binary, case),
     "fit": lambda: check_fit(binary, case)}[mode]()


if __name__ == "__main__":
    main()
