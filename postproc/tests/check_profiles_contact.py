#!/usr/bin/python3
"""rollsim_post profiles --rollsim: the wheel placed as rollsim places it and the contact
patches rollsim check finds, against the profiles as the Python reader draws them (a second
reader of the same files):
  - each patch's point lies on the drawn rail (z of the rail polyline at its y, to the printed
    1e-4 mm plus the polyline's interpolation, 2e-4 mm);
  - the first patch's point is where the drawn wheel touches the drawn rail: their vertical gap
    there is below 1e-3 mm (the wheel drawn at rollsim's lateral shift and lowered by the
    Python reader's own rigid contact search), and nowhere is the gap negative (-1e-9);
  - the figure shows as many patches as rollsim check reports.

Usage: check_profiles_contact.py ROLLSIM POST CASE.yaml WORKDIR
"""
import csv
import os
import re
import subprocess
import sys

import numpy as np

rollsim, post, case, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
check = subprocess.run([rollsim, "check", case], capture_output=True, text=True, check=True).stdout
npatch = int(re.search(r"^wheel_rail\.patches: (\d+)", check, re.M).group(1))
png, data = os.path.join(work, "contact.png"), os.path.join(work, "contact.csv")
r = subprocess.run([sys.executable, post, "profiles", case, "-o", png, "--data", data,
                    "--rollsim", rollsim], capture_output=True, text=True,
                   env=dict(os.environ, MPLBACKEND="Agg"))
if r.returncode != 0:
    sys.exit(f"FAIL rollsim_post profiles: {r.stderr}")
series = {}
for row in csv.DictReader(open(data)):
    series.setdefault(row["series"], []).append((float(row["x"]), float(row["y"])))
rail = np.array(sorted(series.pop("rail")))
wheel = np.array(sorted(next(v for k, v in series.items() if k.startswith("wheel"))))
patches = [v[0] for k, v in sorted(series.items()) if k.startswith("patch")]
failures = 0


def check_(what, ok, detail):
    global failures
    print(f"{'ok  ' if ok else 'FAIL'} {what}: {detail}")
    failures += not ok


check_("patches drawn = patches found", len(patches) == npatch, f"{len(patches)} / {npatch}")
for k, (y, z) in enumerate(patches):
    zr = float(np.interp(y, rail[:, 0], rail[:, 1]))
    check_(f"patch {k + 1} on the drawn rail", abs(zr - z) <= 2e-4, f"z {z:.5f} against {zr:.5f}")
lo, hi = max(rail[0, 0], wheel[0, 0]), min(rail[-1, 0], wheel[-1, 0])
ys = np.union1d(rail[:, 0], wheel[:, 0])
ys = ys[(ys >= lo) & (ys <= hi)]
gap = np.interp(ys, rail[:, 0], rail[:, 1]) - np.interp(ys, wheel[:, 0], wheel[:, 1])
check_("the drawn wheel does not cut into the drawn rail", gap.min() >= -1e-9,
       f"smallest gap {gap.min():.3g} mm")
y1 = patches[0][0]
g1 = float(np.interp(y1, rail[:, 0], rail[:, 1]) - np.interp(y1, wheel[:, 0], wheel[:, 1]))
check_("the drawn wheel touches the rail at patch 1", abs(g1) <= 1e-3, f"gap {g1:.3g} mm")
sys.exit(1 if failures else 0)
