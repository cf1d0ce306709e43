#!/usr/bin/python3
"""The creepages `rollsim check` prints for a wheel-rail patch (docs/model.md §21) against the
closed forms of rigid-body kinematics for the wheelset rolling along the track at V, yawed by
psi, its wheel turning at omega, at the patch's printed rolling radius r and contact angle
delta (profiles' z downward, y toward the track centre); the yawed wheel's contact point lies
below its axle by h = r / sqrt(1 + tan^2(delta) sin^2(psi)) and ahead of it by
-h tan(delta) tan(psi), where the wheel's tangent plane is the patch's (docs/model.md §20 "Yaw"):
    xi = 1 - omega h cos(psi) / V,  eta = -omega h sin(psi) / (V cos(delta)),
    phi = omega cos(psi) sin(delta) / V.
Tolerance: what the printed inputs' digits allow (r to 1e-4 mm, delta to 1e-4 deg, the
creepages to 6 significant digits), doubled.

Usage: check_wr_creepages.py ROLLSIM CASE V OMEGA PSI [LATERAL]
"""
import math
import re
import subprocess
import sys

rollsim, case, V, omega, psi = sys.argv[1], sys.argv[2], *map(float, sys.argv[3:6])
lateral = sys.argv[6] if len(sys.argv) > 6 else "0"
out = subprocess.run([rollsim, "check", case, "--set", f"rolling.velocity={V}", "--set",
                      f"profiles.wheel_angular_velocity={omega}", "--set", f"profiles.yaw={psi}",
                      "--set", f"profiles.lateral_displacement={lateral}"],
                     capture_output=True, text=True, check=True).stdout


def value(key):
    m = re.search(rf"^wheel_rail\.patch1\.{key}: (.*?)  #", out, re.M)
    if not m:
        sys.exit(f"FAIL no {key} in the output:\n{out}")
    return [float(x) for x in re.findall(r"[-+0-9.eE]+", m.group(1))]


r, delta = value("rolling_radius")[0], math.radians(value("contact_angle")[0])
xi, eta, phi = value("creepages")
h = r / math.sqrt(1.0 + (math.tan(delta) * math.sin(psi)) ** 2)
want = (1.0 - omega * h * math.cos(psi) / V, -omega * h * math.sin(psi) / (V * math.cos(delta)),
        omega * math.cos(psi) * math.sin(delta) / V)
dr, dd = 5e-5, math.radians(5e-5)  # half the printed last digits of r and delta
# their effect: h within dr + r tan(delta)/cos^2(delta) sin^2(psi) dd, 1/cos(delta) within
# tan(delta)/cos(delta) dd
dh = dr + r * abs(math.tan(delta)) / math.cos(delta) ** 2 * math.sin(psi) ** 2 * dd
tols = (omega * dh / V,
        omega * abs(math.sin(psi)) * (dh + h * abs(math.tan(delta)) * dd) / (V * math.cos(delta)),
        omega * dd / V)
failures = 0
for name, got, w, t in zip(("xi", "eta", "phi (1/mm)"), (xi, eta, phi), want, tols):
    tol = 2.0 * (t + 5e-6 * abs(w))
    ok = abs(got - w) <= tol
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: got {got:.6g}, want {w:.6g} (tol {tol:.2g})")
sys.exit(1 if failures else 0)
