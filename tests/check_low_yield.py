#!/usr/bin/env python3
"""Issue 42: a steady 3D creep curve with a low yield limit costs about what the elastic curve costs.

The Eurosprinter contact of bench/cases/tractcurve_plast.yaml (a/b = 0.5, F_n = 106.7 kN,
mu = 0.33, mu p0 = 212 N/mm^2) with tau_c0 = 42 N/mm^2 = 0.2 mu p0, the low end of the
issue's range, on 22 x 22 cells (or CELLS x CELLS): one sweep over k_rel = 0.01 and 0.003 and the bench's 30
creepages from -25 % (from rest: the whole contact slides) down to -0.001 %. Cells yield
almost at once and harden up to the friction bound over a zone from tau_c0 to mu p_n, where
the friction weight of weak hardening alone left steady Newton cycling (thousands of
iterations at the start from rest and at -2 % and -1 %). The budget: each of the two plastic
lines within 3 times the Newton iterations of the elastic line over the same creepages
(issue 42: no series above 3 x the elastic one), so the sweep within 6 x the elastic count.
Also checked: every point solved; F_x/(mu F_n) falls with |xi| on each line and stays at
most 1; the weaker hardening's traction is nowhere above the stronger's (its yield limit is
lower at every u*); with hardening the steady state is unique, so the sweep's point at
-7.5 % equals the same point solved from rest (to 1e-6 of mu F_n; the continuation reaches it
after halved steps at 32 x 32, where a failed step used to end in rolling the material,
thousands of iterations); at -25 % the contact is near full sliding, F_x/(mu F_n) within 5 % of 1:
only a zone at the leading edge does not slide, where the flow takes up the creepage until
u* reaches (mu p_n - tau_c0)/k_tau, at most 0.68 mm at k_rel 0.003 over |xi| = 0.25, i.e. 2.7 mm
of 2a = 12.6 mm, which carries 11 % of the load (Hertz) at tractions from tau_c0 up to mu p_n.
Usage: check_low_yield.py ROLLSIM WORKDIR [CELLS]
"""
import os
import subprocess
import sys

import netCDF4

from solver_checks import Checks, eurosprinter, plastic_and_elastic

CREEPAGES = [-0.25, -0.225, -0.2, -0.175, -0.15, -0.125, -0.1, -0.075, -0.05, -0.04, -0.03,
             -0.02, -0.01, -0.008, -0.006, -0.0056, -0.0052, -0.0048, -0.0044, -0.004,
             -0.0036, -0.0032, -0.0028, -0.0024, -0.002, -0.0016, -0.0012, -0.0008, -0.0004,
             -1.0e-5]
CELLS = int(sys.argv[3]) if len(sys.argv) > 3 else 22
CASE = eurosprinter(f"low yield limit: Eurosprinter contact, tau_c0 = 0.2 mu p0, {CELLS}^2 cells",
                    CELLS) + f"""plasticity: {{tau_c0: 42.0, k_rel: 0.3}}
rolling: {{velocity: 10000.0, creepage: 0.0}}
simulation: {{mode: steady}}
output: {{fields: []}}
sweep:
  plasticity.k_rel: [0.01, 0.003]
  rolling.creepage: [{", ".join(repr(x) for x in CREEPAGES)}]
"""
check = Checks()


def main():
    binary, work = sys.argv[1], sys.argv[2]
    runs = plastic_and_elastic(check, binary, work, "low_yield", CASE,
                               ["--set", "plasticity=null", "--set", "sweep.plasticity.k_rel=null"])
    if runs is None:
        return 1
    path, plastic_nc, _, plastic, elastic = runs
    n = len(CREEPAGES)
    check("every plastic point solved", plastic[0] == 2 * n and plastic[1] == 0, f"{plastic}")
    budget = 2 * 3 * elastic[2]
    check("Newton iterations within 3 x the elastic line's per line", plastic[2] <= budget,
          f"{plastic[2]} against {budget} (elastic line {elastic[2]})")
    with netCDF4.Dataset(plastic_nc) as d:
        tc = d["traction_coefficient"][:] / 0.33
    for k, row in zip(["0.01", "0.003"], tc):
        check(f"k_rel {k}: near full sliding at -25 %", 0.95 <= row[0] <= 1.0 + 1e-9,
              f"{row[0]:.8f}")
        falling = all(a >= b for a, b in zip(row[:-1], row[1:]))
        check(f"k_rel {k}: F_x/(mu F_n) falls with |xi| falling and stays at most 1",
              falling and max(row) <= 1.0 + 1e-9, " ".join(f"{v:.5f}" for v in row))
    check("k_rel 0.003 nowhere above k_rel 0.01", all(b <= a + 1e-9 for a, b in zip(*tc)))
    single = os.path.join(work, "from_rest.nc")
    p = subprocess.run([binary, "run", path, "-o", single, "--quiet", "--set", "sweep=null",
                        "--set", "plasticity.k_rel=0.003", "--set", "rolling.creepage=-0.075"],
                       capture_output=True, text=True, timeout=300)
    check("the point at -7.5 % solved from rest", p.returncode == 0,
          p.stderr.strip() if p.returncode else "")
    if p.returncode == 0:
        with netCDF4.Dataset(single) as d:
            alone = float(d["traction_coefficient"][-1]) / 0.33
        k = CREEPAGES.index(-0.075)
        check("k_rel 0.003 at -7.5 %: the sweep's point equals the one from rest (unique state)",
              abs(tc[1][k] - alone) <= 1e-6, f"{tc[1][k]:.9f} vs {alone:.9f}")
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
