#!/usr/bin/env python3
"""Energy balance of steady rolling (docs/model.md §7): the work rate of the rigid slip,
-V (xi F_x + eta F_y + phi M_z), equals the frictional plus the plastic dissipation in the
continuum; the first-order upwind material derivative dissipates the difference, so the
deficit 1 - (P_fric + P_plast)/work falls like the cell size.

  check_energy_balance.py ROLLSIM CASE DIR CELLS... [-- --set ...]

Solves CASE (steady) on each grid (CELLS: "100" in 2D, "32x32" in 3D) and asserts that
the observed order log2(deficit(h)/deficit(h/2)) of every successive pair lies in [0.8, 1.2]
(first order; the asymptotic range is reached from about 16 cells across the contact) and
that the deficit is positive (the scheme adds dissipation, never removes it).
"""
import math
import os
import subprocess
import sys

import netCDF4


def ratio(path):
    with netCDF4.Dataset(path) as d:
        def g(k):
            return float(d[k][:].ravel()[-1]) if k in d.variables else 0.0
        work = -g("velocity") * (g("creepage") * g("Fx") + g("lateral_creepage") * g("Fy")
                                 + g("spin") * g("Mz"))
        return (g("frictional_power") + g("plastic_power")) / work, d.dimensions["x"].size


def main():
    args = sys.argv[1:]
    sets = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    rollsim, case, work = args[:3]
    cells = args[3:]
    os.makedirs(work, exist_ok=True)
    deficits, nxs = [], []
    for m in cells:
        out = os.path.join(work, f"energy_{m}.nc")
        grid = "grid.cells=[%s]" % ", ".join(m.split("x")) if "x" in m else f"grid.cells={m}"
        subprocess.run([rollsim, "run", case, "--quiet", "--set", "simulation.mode=steady",
                        "--set", grid, "-o", out] + sets, check=True, stdout=subprocess.DEVNULL)
        r, nx = ratio(out)
        deficits.append(1.0 - r)
        nxs.append(nx)
        print(f"{nx} cells along x: (P_fric + P_plast) / work = {r:.6f}, deficit {1 - r:.3e}")
    ok = all(d > 0 for d in deficits)
    for (m1, d1), (m2, d2) in zip(zip(nxs, deficits), zip(nxs[1:], deficits[1:])):
        order = math.log(d1 / d2) / math.log(m2 / m1) if d1 > 0 and d2 > 0 else float("nan")
        good = 0.8 <= order <= 1.2
        ok = ok and good
        print(f"{m1} -> {m2} cells: observed order {order:.3f} {'ok' if good else 'FAIL'}")
    if not ok:
        print("FAIL: the energy deficit does not fall at first order")
        sys.exit(1)


if __name__ == "__main__":
    main()
