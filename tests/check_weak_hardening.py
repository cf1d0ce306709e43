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
import sys

import netCDF4

from solver_checks import Checks, eurosprinter, plastic_and_elastic

CASE = eurosprinter("weak hardening: Eurosprinter contact, 22 x 22 cells", 22) + """plasticity: {tau_c0: 150.0, k_rel: 0.3}
rolling: {velocity: 10000.0, creepage: 0.0}
simulation: {mode: steady}
output: {fields: []}
sweep:
  plasticity.k_rel: [0.01, 0.003]
  rolling.creepage: [-0.04, -0.03, -0.02, -0.01, -0.008, -0.006, -0.004]
"""
check = Checks()


def main():
    binary, work = sys.argv[1], sys.argv[2]
    runs = plastic_and_elastic(check, binary, work, "weak_hardening", CASE,
                               ["--set", "plasticity=null", "--set", "sweep.plasticity.k_rel=null"])
    if runs is None:
        return 1
    _, plastic_nc, _, plastic, elastic = runs
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
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
