#!/usr/bin/env python3
"""Issue 42: a steady 3D creep curve with softening costs about what the elastic curve costs.

The Eurosprinter contact of bench/cases/tractcurve_plast.yaml (a/b = 0.5, F_n = 106.7 kN,
mu = 0.33, tau_c0 = 150 N/mm^2 below mu p0 = 212 N/mm^2) with k_rel = -0.01, on 32 x 32
cells, over the bench's 30 creepages from -0.001 % to -25 % in this order. With softening a yielding cell's
limit falls as it flows, and continuation steps whose Newton failed, or whose zero the
steady check refused, used to end in rolling the material from the last point: 5,271 Newton
iterations for the curve. The budget: 3 times the Newton iterations of the elastic curve over
the same creepages (issue 42: no series above 3 x the elastic one). Also checked: every point
solved (each one passed rollsim's cell-by-cell check of a steady state); F_x/(mu F_n) at most
1; at xi = -0.001 % nothing yields (the largest traction, about G a xi ~ 5 N/mm^2, is far below
tau_c0), so the point equals the elastic curve's to 1e-9 of mu F_n; and the curve falls
beyond its peak, as the softened layer carries less the more it flows.
Usage: check_softening_curve.py ROLLSIM WORKDIR
"""
import sys

import netCDF4

from solver_checks import Checks, plastic_and_elastic, softening_sweep

CREEPAGES = [-1.0e-5, -0.0004, -0.0008, -0.0012, -0.0016, -0.002, -0.0024, -0.0028, -0.0032,
             -0.0036, -0.004, -0.0044, -0.0048, -0.0052, -0.0056, -0.006, -0.008, -0.01, -0.02,
             -0.03, -0.04, -0.05, -0.075, -0.1, -0.125, -0.15, -0.175, -0.2, -0.225, -0.25]
CASE = softening_sweep("softening: Eurosprinter contact, k_rel = -0.01, 32 x 32 cells", 32,
                       CREEPAGES)
check = Checks()


def main():
    binary, work = sys.argv[1], sys.argv[2]
    runs = plastic_and_elastic(check, binary, work, "softening", CASE, ["--set", "plasticity=null"])
    if runs is None:
        return 1
    _, plastic_nc, elastic_nc, plastic, elastic = runs
    n = len(CREEPAGES)
    check("every point solved", plastic[0] == n and plastic[1] == 0, f"{plastic}")
    budget = 3 * elastic[2]
    check("Newton iterations within 3 x the elastic curve's", plastic[2] <= budget,
          f"{plastic[2]} against {budget}")
    with netCDF4.Dataset(plastic_nc) as d:
        tc = d["traction_coefficient"][:] / 0.33
    with netCDF4.Dataset(elastic_nc) as d:
        te = d["traction_coefficient"][:] / 0.33
    check("F_x/(mu F_n) at most 1", max(tc) <= 1.0 + 1e-9, f"{max(tc):.9f}")
    check("at -0.001 % the elastic point (nothing yields)", abs(tc[0] - te[0]) <= 1e-9,
          f"{tc[0]:.12f} vs {te[0]:.12f}")
    peak = max(range(n), key=lambda k: tc[k])
    falling = all(tc[k + 1] <= tc[k] + 1e-12 for k in range(peak, n - 1))
    check("beyond the peak the curve falls with |xi|", 0 < peak < n - 1 and falling,
          " ".join(f"{v:.5f}" for v in tc))
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
