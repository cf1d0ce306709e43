#!/usr/bin/python3
"""rollsim_post profiles against rollsim check: two readers of the same profile files (the C
one in src/io/profile.c, the Python one in rollsim_post/profiles.py) must give the same
profiles. `rollsim check` prints each profile's lateral and height ranges (the rail's after
its inclination) to 0.001 mm; the figure's --data rows must have the same ranges to within
that rounding (6e-4 mm), the wheel's lateral range and height span likewise, and the marked
first point of contact must lie on the rail as drawn.

Usage: check_profiles_plot.py ROLLSIM POST CASE.yaml WORKDIR
"""
import csv
import os
import re
import subprocess
import sys

rollsim, post, case, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)
out = subprocess.run([rollsim, "check", case], capture_output=True, text=True)
assert out.returncode == 0, out.stderr
num = r"(-?[0-9.]+)"
rng = rf"y {num} \.\. {num}, z {num} \.\. {num}"
rail = [float(v) for v in re.search(r"the rail inclined: " + rng, out.stdout).groups()]
wheel = [float(v) for v in re.search(r"profiles.wheel: .*points, " + rng, out.stdout).groups()]

png, data = os.path.join(work, "profiles.png"), os.path.join(work, "profiles.csv")
env = dict(os.environ, MPLBACKEND="Agg")
r = subprocess.run([sys.executable, post, "profiles", case, "-o", png, "--data", data],
                   capture_output=True, text=True, env=env)
assert r.returncode == 0, r.stderr
assert os.path.getsize(png) > 10000, "the figure is empty"
rows = list(csv.DictReader(open(data)))
series = {}
for row in rows:
    series.setdefault(row["series"].split(" ")[0], []).append((float(row["x"]), float(row["y"])))
failures = 0


def near(what, got, want, tol=6e-4, source="rollsim check"):
    global failures
    ok = abs(got - want) <= tol
    print(f"{'ok' if ok else 'FAIL'}: {what}: {got:.6f} ({source} {want:.6f})")
    failures += not ok


ry = [p[0] for p in series["rail"]]
rz = [p[1] for p in series["rail"]]
near("rail y min", min(ry), rail[0])
near("rail y max", max(ry), rail[1])
near("rail z min", min(rz), rail[2])
near("rail z max", max(rz), rail[3])
wy = [p[0] for p in series["wheel"]]
wz = [p[1] for p in series["wheel"]]
near("wheel y min", min(wy), wheel[0])
near("wheel y max", max(wy), wheel[1])
near("wheel height span", max(wz) - min(wz), wheel[3] - wheel[2], 1.2e-3)
(cy, cz), = series["first"]
# the rail's polyline at cy (its points are sorted by y: a z(y) profile)
pts = sorted(series["rail"])
k = max(i for i, p in enumerate(pts) if p[0] <= cy)
(y0, z0), (y1, z1) = pts[k], pts[min(k + 1, len(pts) - 1)]
zr = z0 + (z1 - z0) * (cy - y0) / (y1 - y0) if y1 != y0 else z0
near("contact point on the rail (z)", cz, zr, 1e-9, "the rail drawn")
print("FAILED" if failures else "all passed")
sys.exit(1 if failures else 0)
