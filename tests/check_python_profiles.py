#!/usr/bin/python3
"""rollsim.sweep on a case with profiles (a path of wheelset positions, the Manchester
benchmark's A-2.2 right wheel) in Python equals the command line's sweep file bit for bit (the
same code on the same input) in every variable; rollsim.run on profiles raises a CaseError
that points to the command line (one file per patch).

Usage: check_python_profiles.py ROLLSIM CASE OUTDIR
"""
import os
import subprocess
import sys

import netCDF4
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "postproc"))
import rollsim  # noqa: E402

rollsim_bin, case, outdir = sys.argv[1:4]
os.makedirs(outdir, exist_ok=True)
out = os.path.join(outdir, "a22_cli.nc")
if os.path.exists(out):
    os.remove(out)
subprocess.run([rollsim_bin, "sweep", case, "-o", out, "--quiet"], check=True, capture_output=True)
ds = rollsim.sweep(case)
failures = 0
with netCDF4.Dataset(out) as nc:
    for name, var in nc.variables.items():
        a = np.ma.filled(var[:].astype(float), np.nan)
        b = ds[name].values.astype(float)
        same = a.shape == b.shape and np.array_equal(a, b, equal_nan=True)
        failures += not same
        if not same:
            print(f"FAIL {name} differs from the command line's")
print(("ok   " if failures == 0 else "FAIL ") +
      f"rollsim.sweep: {len(ds.position)} positions, every variable as the command line's")
try:
    rollsim.run(case)
    print("FAIL rollsim.run on profiles did not raise")
    failures += 1
except rollsim.CaseError as e:
    ok = "one file per contact patch" in str(e) and "rollsim run" in str(e)
    failures += not ok
    print(("ok   " if ok else "FAIL ") + f"rollsim.run raises: {e}")
sys.exit(1 if failures else 0)
