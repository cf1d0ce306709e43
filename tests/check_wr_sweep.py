#!/usr/bin/python3
"""rollsim sweep on profiles (cases/profiles/mbench_a22_right.yaml: 21 wheelset positions, each
with its own lateral displacement, yaw and wheel angular velocity) and its file
(docs/file-format.md "Wheel-rail sweep files"):

- every position solved (status "complete", converged 1) and the file's swept keys are the case's
  lists, position by position;
- the creepages of each patch against the closed forms of rigid-body kinematics at the file's
  rolling radius and contact angle with that position's V, yaw and omega (docs/model.md §21),
  the yawed wheel's contact point below its axle by h = r / sqrt(1 + tan^2(delta) sin^2(psi))
  and ahead of it by -h tan(delta) tan(psi) (§20 "Yaw"): xi = 1 - omega h cos(psi)/V,
  eta = -omega h sin(psi) / (V cos(delta)), phi = omega cos(psi) sin(delta)/V, to 1e-12
  (rounding): a position solved with another position's yaw or omega differs by 1e-6 or more;
- the vertical balance: the wheel's vertical force, tangential forces included (Fz_track, and
  sum F_n cos(delta) - F_s sin(delta) recomputed here), is the wheel load to 2e-6 (the balance's
  tolerance 1e-6, doubled);
- the track forces are the patch forces turned by the contact angle: Fz_track + sum F_s
  sin(delta) = sum F_n cos(delta), Fy_track = sum (F_s cos(delta) + F_n sin(delta)),
  Fx_track = sum F_x, to 1e-9 relative;
- the flange: at 8 mm the contact angle exceeds 60 deg and F_n exceeds the wheel load by more
  than 20 % (one patch: F_n cos(delta) - F_s sin(delta) = F_z with |F_s| <= mu F_n gives F_n >=
  F_z / (cos(delta) + mu sin(delta)), 1.32 F_z at 60 deg), on the tread at 2 mm it is under
  10 deg;
- positions 5 (2 mm) and 17 (8 mm) against `rollsim check` with the same keys set: F_n, F_x, F_s
  to the 6 digits check prints.

Usage: check_wr_sweep.py ROLLSIM CASE OUTDIR
"""
import math
import os
import re
import subprocess
import sys

import netCDF4
import yaml

rollsim, case, outdir = sys.argv[1:4]
os.makedirs(outdir, exist_ok=True)
out = os.path.join(outdir, "a22_right.nc")
if os.path.exists(out):
    os.remove(out)
subprocess.run([rollsim, "sweep", case, "-o", out, "--quiet"], check=True)
with open(case) as f:
    spec = yaml.safe_load(f)
load = spec["profiles"]["vertical_load"]
V = spec["rolling"]["velocity"]

failures = 0


def check(ok, what):
    global failures
    if not ok:
        failures += 1
    print(("ok   " if ok else "FAIL ") + what)


def listed(v, n):
    if isinstance(v, dict):
        a, b, k = v["linspace"]
        return [a + (b - a) * i / (k - 1) for i in range(int(k))]
    return v


with netCDF4.Dataset(out) as nc:
    v = {k: nc.variables[k][:].filled(math.nan) for k in nc.variables}
    status = nc.getncattr("status")
n = len(v["lateral_displacement"])
check(status == "complete" and n == 21 and all(v["converged"] == 1), f"status {status!r}, {n} positions")
for key in ("lateral_displacement", "yaw", "wheel_angular_velocity"):
    want = listed(spec["sweep"]["profiles." + key], n)
    err = max(abs(a - b) for a, b in zip(v[key], want))
    check(err <= 1e-12 * max(1.0, max(abs(x) for x in want)), f"{key} as listed (|diff| {err:.2g})")

worst = [0.0, 0.0, 0.0]
for i in range(n):
    psi, omega = v["yaw"][i], v["wheel_angular_velocity"][i]
    fz = fy = fx = fn_vert = 0.0
    for k in range(int(v["patches"][i])):
        r, d = v["rolling_radius"][i, k], v["contact_angle"][i, k]
        h = r / math.sqrt(1.0 + (math.tan(d) * math.sin(psi)) ** 2)
        want = (1 - omega * h * math.cos(psi) / V, -omega * h * math.sin(psi) / (V * math.cos(d)),
                omega * math.cos(psi) * math.sin(d) / V)
        for j, name in enumerate(("xi", "eta", "phi")):
            worst[j] = max(worst[j], abs(v[name][i, k] - want[j]))
        fn, fs = v["Fn"][i, k], v["Fs"][i, k]
        fn_vert += fn * math.cos(d)
        fz += -fs * math.sin(d) + fn * math.cos(d)
        fy += fs * math.cos(d) + fn * math.sin(d)
        fx += v["Fx"][i, k]
    check(abs(fz - load) <= 2e-6 * load and abs(v["Fz_track"][i] - load) <= 2e-6 * load,
          f"position {i + 1}: vertical force {fz:.9g} N (load {load:g} N; F_n cos(delta) alone "
          f"{fn_vert:.6g} N)")
    scale = max(abs(fz), abs(fy), abs(fx), 1.0)
    err = max(abs(fz - v["Fz_track"][i]), abs(fy - v["Fy_track"][i]), abs(fx - v["Fx_track"][i]))
    check(err <= 1e-9 * scale, f"position {i + 1}: track forces (|diff| {err:.2g} N)")
check(max(worst) <= 1e-12, f"creepages against the closed forms: largest |diff| xi {worst[0]:.2g}, "
      f"eta {worst[1]:.2g}, phi {worst[2]:.2g}")

tread, flange = 4, 16  # 2 mm and 8 mm
check(math.degrees(v["contact_angle"][tread, 0]) < 10.0,
      f"2 mm: on the tread ({math.degrees(v['contact_angle'][tread, 0]):.2f} deg)")
check(math.degrees(v["contact_angle"][flange, 0]) > 60.0 and v["Fn"][flange, 0] > 1.2 * load,
      f"8 mm: on the flange ({math.degrees(v['contact_angle'][flange, 0]):.2f} deg, "
      f"F_n {v['Fn'][flange, 0]:.0f} N)")

for i in (tread, flange):
    p = subprocess.run([rollsim, "check", case, "--set", "sweep=null",
                        "--set", f"profiles.lateral_displacement={v['lateral_displacement'][i]!r}",
                        "--set", f"profiles.yaw={v['yaw'][i]!r}",
                        "--set", f"profiles.wheel_angular_velocity={v['wheel_angular_velocity'][i]!r}"],
                       capture_output=True, text=True, check=True).stdout
    fn = float(re.search(r"^wheel_rail\.patch1\.normal_force: (\S+)", p, re.M).group(1))
    tang = re.search(r"^wheel_rail\.patch1\.tangential: \[(\S+), (\S+),", p, re.M)
    got = (fn, float(tang.group(1)), float(tang.group(2)))
    file = (v["Fn"][i, 0], v["Fx"][i, 0], v["Fs"][i, 0])
    ok = all(abs(a - b) <= 6e-6 * max(abs(b), 1.0) for a, b in zip(got, file))
    check(ok, f"position {i + 1} against rollsim check: {got} / {tuple(round(x, 3) for x in file)}")

sys.exit(1 if failures else 0)
