#!/usr/bin/env python3
"""Issue 42: steady 3D creep curves with weak hardening cost about what the elastic curve costs.

The Eurosprinter contact of bench/cases/tractcurve_plast.yaml (a/b = 0.5, F_n = 106.7 kN,
mu = 0.33, tau_c0 = 150 N/mm^2 below mu p0 = 212 N/mm^2) on 22 x 22 cells, one sweep over
k_rel = 0.01 and 0.003 and the creepages -4 % ... -0.4 % where Newton cycled between the
slip + yield and the yield-only branch of the cells that hardened up to the friction bound
(the curve starts from rest at -4 %). The budget: each of the two plastic lines within 3
times the Newton iterations of the elastic line over the same creepages (issue 42: no series
above 3 x the elastic one), so the sweep within 6 x the elastic count. Also checked: every
point solved, and F_x/(mu F_n) rising with |xi| on each line (a creep curve) and at most 1 (|F| <= mu F_n).
Usage: check_weak_hardening.py ROLLSIM WORKDIR
"""
import os
import re
import subprocess
import sys

import netCDF4

CASE = """title: "weak hardening: Eurosprinter contact, 22 x 22 cells"
contact: {dimension: 3, normal_load: 106700.0, radius: [625.0, 1776.72]}
grid: {cells: [22, 22], extent: [1.1, 1.1]}
material: {shear_modulus: 82000.0, poisson_ratio: 0.28}
friction: {mu: 0.33}
plasticity: {tau_c0: 150.0, k_rel: 0.3}
rolling: {velocity: 10000.0, creepage: 0.0}
simulation: {mode: steady}
output: {fields: []}
sweep:
  plasticity.k_rel: [0.01, 0.003]
  rolling.creepage: [-0.04, -0.03, -0.02, -0.01, -0.008, -0.006, -0.004]
"""
failures = 0


def check(what, ok, detail=""):
    global failures
    print(f"{'ok  ' if ok else 'FAIL'} {what}{': ' + detail if detail else ''}")
    if not ok:
        failures += 1


def sweep(binary, path, out, extra):
    p = subprocess.run([binary, "sweep", path, "-o", out, "--quiet"] + extra,
                       capture_output=True, text=True, timeout=300)
    m = re.search(r"(\d+) points solved, (\d+) failed, Newton iterations (\d+)", p.stdout)
    if p.returncode != 0 or not m:
        print(p.stdout, p.stderr)
        return None
    return int(m.group(1)), int(m.group(2)), int(m.group(3))


def main():
    binary, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    path = os.path.join(work, "weak_hardening.yaml")
    with open(path, "w") as f:
        f.write(CASE)
    plastic_nc = os.path.join(work, "weak_hardening.nc")
    plastic = sweep(binary, path, plastic_nc, [])
    elastic = sweep(binary, path, os.path.join(work, "elastic.nc"),
                    ["--set", "plasticity=null", "--set", "sweep.plasticity.k_rel=null"])
    check("the plastic sweep ran", plastic is not None)
    check("the elastic sweep ran", elastic is not None)
    if plastic is None or elastic is None:
        return 1
    check("every plastic point solved", plastic[0] == 14 and plastic[1] == 0, f"{plastic}")
    budget = 2 * 3 * elastic[2]
    check("Newton iterations within 3 x the elastic line's per line", plastic[2] <= budget,
          f"{plastic[2]} against {budget} (elastic line {elastic[2]})")
    with netCDF4.Dataset(plastic_nc) as d:
        tc = d["traction_coefficient"][:] / 0.33
    for k, row in zip(["0.01", "0.003"], tc):
        rising = all(a > b for a, b in zip(row[:-1], row[1:]))
        check(f"k_rel {k}: F_x/(mu F_n) falls with |xi| falling and stays at most 1",
              rising and max(row) <= 1.0 + 1e-9, " ".join(f"{v:.5f}" for v in row))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
