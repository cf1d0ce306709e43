#!/usr/bin/python3
"""Checks of `rollsim run CASE --restart OLD.nc` (issue 4 item 3).

  check_restart.py agree FULL.nc FIRST.nc RESTARTED.nc TOL [FIELD...]
      RESTARTED continues FIRST: its first record is FIRST's last (same time, same state),
      its output times are FULL's from there on, and at every common time F_x (relative)
      and the fields (max-norm, relative to the field's max |.| over FULL's records) agree
      with FULL within TOL. Also: status complete, history names the restart file.
  check_restart.py error EXPECTED_SUBSTRING ROLLSIM ARGS...
      the command exits 2, says EXPECTED_SUBSTRING on stderr, and writes no -o file.
"""
import os
import subprocess
import sys

import netCDF4
import numpy as np


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def agree(full_path, first_path, rst_path, tol, fields):
    full = netCDF4.Dataset(full_path)
    first = netCDF4.Dataset(first_path)
    rst = netCDF4.Dataset(rst_path)
    if rst.status != "complete":
        fail(f"{rst_path}: status {rst.status!r}")
    if os.path.basename(first_path) not in rst.history or "restart" not in rst.history:
        fail(f"{rst_path}: history does not name the restart file: {rst.history!r}")
    # history accumulates: the old file's lines, then one line for the restarted run
    old_lines, new_lines = first.history.split("\n"), rst.history.split("\n")
    if new_lines[:-1] != old_lines or f"its status was '{first.status}'" not in new_lines[-1]:
        fail(f"{rst_path}: history is not {first_path}'s plus one line naming its status: {rst.history!r}")
    tf, t1, tr = full["time"][:], first["time"][:], rst["time"][:]
    # The restarted run starts with the record at the old run's last time, in its state.
    if tr[0] != t1[-1]:
        fail(f"first record at t = {tr[0]!r}, the restart file ends at {t1[-1]!r}")
    for v in ["px", "upl", "ustar"]:
        if not np.array_equal(rst[v][0], first[v][-1]):
            fail(f"{v} of the first record differs from the restart file's last record")
    # Same output grid as the uninterrupted run from t0 on.
    later = tf[tf >= tr[0] * (1 - 1e-12)]
    if len(later) != len(tr) or np.max(np.abs(later - tr)) > 1e-12 * tf[-1]:
        fail(f"output times differ: {tr} vs {later}")
    j0 = len(tf) - len(tr)
    worst = {}
    fx_full = full["Fx"][j0:]
    worst["Fx"] = np.max(np.abs(rst["Fx"][:] - fx_full) / np.abs(fx_full))
    for v in fields:
        a = full[v][j0:]
        scale = np.max(np.abs(a))
        if scale == 0.0:
            fail(f"{v} is zero in {full_path}: nothing to compare")
        worst[v] = np.max(np.abs(rst[v][:] - a)) / scale
    print(f"restart vs uninterrupted over {len(tr)} records (t = {tr[0]:.6g} .. {tr[-1]:.6g} s):",
          ", ".join(f"{k} {e:.3g}" for k, e in worst.items()), f"(tol {tol:g})")
    bad = {k: e for k, e in worst.items() if not e <= tol}
    if bad:
        fail(f"restart differs from the uninterrupted run: {bad}")
    print("OK")


def error(expect, cmd):
    out = cmd[cmd.index("-o") + 1] if "-o" in cmd else None
    old = cmd[cmd.index("--restart") + 1] if "--restart" in cmd else None
    same = out is not None and old is not None and os.path.realpath(out) == os.path.realpath(old)
    if same:  # the restart file must come out untouched
        with open(old, "rb") as f:
            before = f.read()
    elif out and os.path.exists(out):
        os.remove(out)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 2:
        fail(f"exit {p.returncode}, expected 2: {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    if expect not in p.stderr:
        fail(f"stderr does not say {expect!r}: {p.stderr!r}")
    if same:
        with open(old, "rb") as f:
            if f.read() != before:
                fail(f"{old} changed although the input was invalid")
    elif out and (os.path.exists(out) or os.path.exists(out + ".part")):
        fail(f"{out} written although the input was invalid")
    print("OK:", p.stderr.strip())


if __name__ == "__main__":
    if sys.argv[1] == "agree":
        agree(sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]), sys.argv[6:])
    elif sys.argv[1] == "error":
        error(sys.argv[2], sys.argv[3:])
    else:
        fail(f"unknown check {sys.argv[1]}")
