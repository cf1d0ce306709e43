#!/usr/bin/python3
"""rollsim run on profiles (cases/profiles/wheel_rail_profiles.yaml: S1002 on UIC60, the
wheelset centred, one patch on the tread): one 3D run file per loaded patch, OUT_patch1.nc.

- steady (simulation.mode: steady): the file's F_x, F_y (= F_s), M_z (= M_n) and F_n are
  those `rollsim check` prints for the patch, to its 6 digits (5e-6 relative), and the wheel's
  vertical force F_n cos(delta) - F_s sin(delta) is the wheel load to 1e-5 (the balance's 1e-6
  and the printed contact angle's 4 decimals); its wheel_rail_patch attribute names the patch;
- transient from rest over 30 mm (six contact lengths, the patch's grid 5 mm long): the last
  record is the steady state to 3e-3 mu F_n (the transient's time tolerance, solver.rtol auto,
  is 3e-3 in 3D: the integration error stays below that; the start-up's own decay is
  exp(-6)-small after six contact lengths);
- the patch's traction map is there: px and py over (time, y, x), nonzero inside the contact
  only (|p| <= mu p_n to 1e-9 relative in every cell).

Usage: check_wr_run.py ROLLSIM CASE OUTDIR
"""
import math
import os
import re
import subprocess
import sys

import netCDF4
import numpy as np

rollsim, case, outdir = sys.argv[1:4]
os.makedirs(outdir, exist_ok=True)
failures = 0


def check(ok, what):
    global failures
    failures += not ok
    print(("ok   " if ok else "FAIL ") + what)


def run(name, *sets):
    out = os.path.join(outdir, f"{name}.nc")
    patch = os.path.join(outdir, f"{name}_patch1.nc")
    if os.path.exists(patch):
        os.remove(patch)
    cmd = [rollsim, "run", case, "-o", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True)
    return netCDF4.Dataset(patch)


printed = subprocess.run([rollsim, "check", case], capture_output=True, text=True,
                         check=True).stdout
tang = [float(x) for x in re.search(r"^wheel_rail\.patch1\.tangential: \[(\S+), (\S+), (\S+)\]",
                                    printed, re.M).groups()]
fn_check = float(re.search(r"^wheel_rail\.patch1\.normal_force: (\S+)", printed, re.M).group(1))
delta = math.radians(float(re.search(r"^wheel_rail\.patch1\.contact_angle: (\S+)", printed,
                                     re.M).group(1)))
mu = 0.3
load = 10000.0

with run("steady", "simulation.mode=steady") as nc:
    got = [float(nc.variables[v][-1]) for v in ("Fx", "Fy", "Mz")]
    fn = float(nc.variables["Fn"][-1])
    patch = nc.getncattr("wheel_rail_patch")
    px, py, pn = (np.asarray(nc.variables[v][-1]) for v in ("px", "py", "pn"))
for name, a, b in zip(("F_x", "F_s", "M_n"), got, tang):
    check(abs(a - b) <= 5e-6 * abs(b), f"steady {name} {a:.6g} against check's {b:.6g}")
fz = fn * math.cos(delta) - got[1] * math.sin(delta)
check(abs(fn - fn_check) <= 5e-6 * fn and abs(fz - load) <= 1e-5 * load,
      f"steady F_n {fn:.9g} N (check's {fn_check:.6g}), vertical force {fz:.9g} N")
check(patch.startswith("patch 1 of 1 at lateral displacement 0 mm"), f"wheel_rail_patch: {patch[:40]}")
excess = np.max(np.hypot(px, py) - mu * pn)
check(excess <= 1e-9 * mu * pn.max() and np.all((np.hypot(px, py) > 0) <= (pn > 0)),
      f"traction map: |p| <= mu p_n (largest excess {excess:.2g} N/mm2), zero outside the contact")

with run("transient", "simulation.mode=transient", "simulation.rolled_distance=30",
         "simulation.output_interval=5e-3") as nc:
    fx = float(nc.variables["Fx"][-1])
    fs = float(nc.variables["Fy"][-1])
    records = len(nc.variables["time"])
for name, a, b in (("F_x", fx, got[0]), ("F_s", fs, got[1])):
    check(abs(a - b) <= 3e-3 * mu * fn,
          f"transient {name} after 30 mm {a:.6g} against steady {b:.6g} "
          f"({abs(a - b) / (mu * fn):.2g} mu F_n, {records} records)")
sys.exit(1 if failures else 0)
