#!/usr/bin/python3
"""The steady tangential problem of a wheel-rail patch (`rollsim check`, docs/model.md §20-21)
against today's 3D solver on the same grid with the gap from radii (an independent path: the
Hertz gap of the radii, not the profiles' polylines, and the creepages given as numbers).

Profiles: a rail crowned with radius RR and a wheel crowned with radius RW, circular arcs as
tables at 0.05 mm spacing; the wheel's angular velocity and yaw give all three creepages. The
check prints the patch's contact angle delta, rolling radius r, normal force, creepages, grid
and forces; the run uses radius [r / cos(delta), RR RW / (RR + RW)] (the two circles' relative
curvature across, the wheel's along the track in the tangent plane), that normal force, those
creepages and that grid. The polylines' gap differs from the radii's by at most the chord
error, d^2/8 (1/RR + 1/RW) = 1.4e-6 mm, 1e-4 of the approach: F_x, F_s within 1e-3 of mu F_n,
M_n within 1e-3 mu F_n times the patch's half-length.

Usage: check_wr_tangential.py ROLLSIM OUTDIR
"""
import math
import os
import re
import subprocess
import sys

import netCDF4

RR, RW, D = 300.0, 500.0, 0.05
rollsim, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)


def table(path, radius, sign):
    """z (downward) of a circle of the radius, crest at y = 0: sign +1 rail, -1 wheel."""
    n = int(40.0 / D) + 1
    with open(path, "w") as f:
        for i in range(n):
            y = -20.0 + 40.0 * i / (n - 1)
            f.write(f"{y:.6f} {sign * (radius - math.sqrt(radius * radius - y * y)):.12f}\n")


table(os.path.join(out, "rail.txt"), RR, 1.0)
table(os.path.join(out, "wheel.txt"), RW, -1.0)
case = os.path.join(out, "crowns.yaml")
with open(case, "w") as f:
    f.write("""title: "two crowns"
material: {shear_modulus: 82000, poisson_ratio: 0.28}
friction: {mu: 0.3}
rolling: {velocity: 2000}
profiles:
  rail: rail.txt
  wheel: wheel.txt
  gauge_height: 0.5
  lateral_displacement: 0.7
  vertical_load: 10000
  yaw: 0.002
  wheel_angular_velocity: 4.3466
""")
check = subprocess.run([rollsim, "check", case], capture_output=True, text=True, check=True).stdout


def value(key):
    m = re.search(rf"^wheel_rail\.patch1\.{key}: (.*?)  #", check, re.M)
    if not m:
        sys.exit(f"FAIL no {key} in the check's output:\n{check}")
    return [float(x) for x in re.findall(r"[-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?", m.group(1))]


if "wheel_rail.patches: 1" not in check:
    sys.exit(f"FAIL not one patch:\n{check}")
delta, r = math.radians(value("contact_angle")[0]), value("rolling_radius")[0]
fn, (xi, eta, phi) = value("normal_force")[0], value("creepages")
(x0, x1), (s0, s1) = [value("grid")[0:2], value("grid")[2:4]]
cells = re.search(r"^wheel_rail\.patch1\.grid: .*# mm, x and s, (\d+) x (\d+) cells", check, re.M)
fx, fs, mn = value("tangential")
nc, hertz = os.path.join(out, "crowns_hertz.nc"), os.path.join(out, "hertz.yaml")
with open(hertz, "w") as f:
    f.write(f"""title: "the patch from radii"
contact: {{dimension: 3, normal_load: {fn!r}, radius: [{r / math.cos(delta)!r}, {RR * RW / (RR + RW)!r}]}}
grid: {{cells: [{cells.group(1)}, {cells.group(2)}], x_range: [{x0!r}, {x1!r}], y_range: [{s0!r}, {s1!r}]}}
material: {{shear_modulus: 82000, poisson_ratio: 0.28}}
friction: {{mu: 0.3}}
rolling: {{velocity: 2000, creepage: {xi!r}, lateral_creepage: {eta!r}, spin: {phi!r}}}
simulation: {{mode: steady}}
output: {{fields: [], error_estimate: false}}
""")
subprocess.run([rollsim, "run", hertz, "-o", nc, "--quiet"], capture_output=True, text=True,
               check=True)
with netCDF4.Dataset(nc) as d:
    hx, hy, hz, hn = (float(d[v][-1]) for v in ("Fx", "Fy", "Mz", "Fn"))
mu_fn = 0.3 * fn
failures = 0
for name, got, want, tol in (("F_n (N)", hn, fn, 1e-6 * fn),
                             ("F_x (N)", fx, hx, 1e-3 * mu_fn), ("F_s (N)", fs, hy, 1e-3 * mu_fn),
                             ("M_n (N mm)", mn, hz, 1e-3 * mu_fn * 0.5 * (x1 - x0))):
    ok = abs(got - want) <= tol
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: profiles {got:.6g}, radii {want:.6g}, "
          f"diff {abs(got - want):.3g} (tol {tol:.3g})")
print(f"(contact angle {math.degrees(delta):.3f} deg, r {r:.4f} mm, creepages {xi:.4g} {eta:.4g} "
      f"{phi:.4g})")
sys.exit(1 if failures else 0)
