#!/usr/bin/python3
"""rollsim_post wheelrail: the plotted series (--data CSV) are the sweep file's values, read
here by netCDF4 directly (a second reader): per patch the contact point's y on the rail, the
contact angle in degrees, F_n, F_x, F_s in kN, and F_y, F_z of the track in kN, each against
the lateral displacement, to 1e-12 relative (the CSV holds repr() of the plotted doubles); the
figure file exists. A moving wheelset's file (rollsim run with a lateral-displacement history)
is drawn against its time, the lateral displacement beside the contact point.

Usage: check_wheelrail_plot.py ROLLSIM POST CASE.yaml WORKDIR
"""
import csv
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np

rollsim, post, case, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
nc_path, png, data = (os.path.join(work, f) for f in ("sweep.nc", "sweep.png", "sweep.csv"))
for f in (nc_path, png, data):
    if os.path.exists(f):
        os.remove(f)
subprocess.run([rollsim, "sweep", case, "-o", nc_path, "--quiet"], check=True,
               capture_output=True)
r = subprocess.run([sys.executable, post, "wheelrail", nc_path, "-o", png, "--data", data],
                   capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
if r.returncode != 0:
    sys.exit(f"FAIL rollsim_post wheelrail: {r.stderr}")
with netCDF4.Dataset(nc_path) as nc:
    v = {k: np.ma.filled(nc.variables[k][:].astype(float), np.nan) for k in nc.variables}
drawn = {}
for row in csv.DictReader(open(data)):
    drawn.setdefault((row["quantity"], row["series"]), []).append((float(row["x"]),
                                                                   float(row["y"])))
want = {("y_mm", "patch 1"): v["rail_y"][:, 0],
        ("angle_deg", "patch 1"): np.degrees(v["contact_angle"][:, 0]),
        ("Fn_kN", "Fn, patch 1"): v["Fn"][:, 0] / 1e3,
        ("Fx_kN", "Fx, patch 1"): v["Fx"][:, 0] / 1e3,
        ("Fs_kN", "Fs, patch 1"): v["Fs"][:, 0] / 1e3,
        ("Fy_kN", "F_y toward the track centre"): v["Fy_track"] / 1e3,
        ("Fz_kN", "F_z up"): v["Fz_track"] / 1e3}
failures = 0
for key, w in want.items():
    got = drawn.get(key)
    ok = got is not None and len(got) == len(w)
    if ok:
        xs, ys = zip(*got)
        ok = all(abs(a - b) <= 1e-12 * max(abs(b), 1.0)
                 for a, b in zip(xs, v["lateral_displacement"])) and \
            all(abs(a - b) <= 1e-12 * max(abs(b), 1.0) for a, b in zip(ys, w))
    print(("ok   " if ok else "FAIL ") + f"{key[1]} ({key[0]}): {len(got or [])} points")
    failures += not ok
ok = os.path.getsize(png) > 20000
print(("ok   " if ok else "FAIL ") + f"figure {png}")
failures += not ok

moving = os.path.join(work, "moving.nc")
subprocess.run([rollsim, "run", case, "-o", moving, "--quiet", "--set", "sweep=null",
                "--set", "simulation.mode=transient", "--set", "simulation.end_time=0.02",
                "--set", "simulation.output_interval=0.01", "--set",
                "profiles.lateral_displacement={ramp: {from: 0, to: 0.5, start: 0, duration: 0.02}}"],
               check=True, capture_output=True)
r = subprocess.run([sys.executable, post, "wheelrail", moving, "-o", png, "--data", data],
                   capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
with netCDF4.Dataset(moving) as nc:
    t = np.ma.filled(nc.variables["time"][:].astype(float), np.nan)
    lat = np.ma.filled(nc.variables["lateral_displacement"][:].astype(float), np.nan)
rows = [row for row in csv.DictReader(open(data))] if r.returncode == 0 else []
drawn = [(float(w["x"]), float(w["y"])) for w in rows
         if w["series"] == "lateral displacement of the wheelset"]
ok = r.returncode == 0 and len(drawn) == len(t) and all(
    abs(a - b) <= 1e-15 and abs(c - e) <= 1e-12 for (a, c), b, e in zip(drawn, t, lat))
print(("ok   " if ok else "FAIL ") + f"moving wheelset: drawn against time, {len(drawn)} points")
failures += not ok
sys.exit(1 if failures else 0)
