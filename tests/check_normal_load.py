#!/usr/bin/env python3
"""Normal-load history (issue 4): run a case whose line load is a sine and check at
every stored time that

  1. F_n equals the load history exactly (the normal problem enforces sum p_n dx = q);
  2. p_n is the discrete normal solution for that load (docs/model.md §3): p_n >= 0, the
     deformed gap h + A_zz p_n - delta vanishes on the contact cells (one delta for all
     of them) and is >= 0 outside; A_zz is rebuilt here from its closed form
     (plane strain, piecewise-constant pressure, Johnson 1985 ch. 2);
  3. the contact grows and shrinks: cells enter and leave it;
  4. the tangential traction respects the moving bound |p_x| <= mu p_n.

usage: check_normal_load.py ROLLSIM CASE WORKDIR
"""
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np
import yaml


def ln_primitive(s):
    return np.where(s == 0.0, 0.0, s * np.log(np.abs(np.where(s == 0.0, 1.0, s))) - s)


def main():
    rollsim, case, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "normal_load.nc")
    subprocess.run([rollsim, "run", case, "-o", out, "--quiet"], check=True)
    ds = netCDF4.Dataset(out)
    cfg = yaml.safe_load(ds.getncattr("case"))
    G = cfg["material"]["shear_modulus"]
    nu = cfg["material"]["poisson_ratio"]
    R = cfg["contact"]["radius"]
    L = cfg["contact"]["reference_length"]
    mu = cfg["friction"]["mu"]
    sine = cfg["contact"]["normal_load"]["sine"]
    x = ds["x"][:].data
    dx = x[1] - x[0]
    n = len(x)
    t = ds["time"][:].data
    Fn = ds["Fn"][:].data
    pn = ds["pn"][:].data
    px = ds["px"][:].data
    fails = []

    # 1. F_n is the history (machine precision up to the sum's rounding).
    q = sine["mean"] + sine["amplitude"] * np.sin(2 * math.pi * sine["frequency"] * t + sine["phase"])
    err = np.max(np.abs(Fn - q) / q)
    print(f"max |F_n - q(t)|/q = {err:.2e} over {len(t)} records")
    if err > 1e-12:
        fails.append(f"F_n differs from the load history by {err:.2e} (rel)")

    # 2. Discrete normal solution: influence matrix A_zz(i - j).
    k = np.arange(-(n - 1), n)
    s = k * dx
    int_ln = ln_primitive(s + dx / 2) - ln_primitive(s - dx / 2)
    coef = 2.0 * (1.0 - nu) / (math.pi * G) * (dx * math.log(L) - int_ln)
    A = coef[(np.arange(n)[:, None] - np.arange(n)[None, :]) + n - 1]
    h = x ** 2 / (2 * R)
    worst_eq = worst_gap = 0.0
    counts = []
    for r in range(len(t)):
        p = pn[r]
        if p.min() < 0:
            fails.append(f"t = {t[r]:.6g}: negative pressure {p.min():.3g}")
        c = p > 0
        counts.append(int(c.sum()))
        gap = h + A @ p
        delta = gap[c]
        scale = np.max(np.abs(A @ p))  # size of the deformation, mm
        worst_eq = max(worst_eq, (delta.max() - delta.min()) / scale)
        worst_gap = max(worst_gap, max(0.0, (delta.mean() - gap[~c]).max(initial=0.0)) / scale)
    print(f"contact cells over the run: {min(counts)} .. {max(counts)} of {n}")
    print(f"max spread of the approach over contact cells / deformation = {worst_eq:.2e}")
    print(f"max penetration outside the contact / deformation = {worst_gap:.2e}")
    # Tolerances: the active-set LU solve is exact up to rounding (condition of A_zz
    # ~ n^2): 1e-9 of the deformation is far below a cell's entering threshold.
    if worst_eq > 1e-9:
        fails.append(f"deformed gap not constant over the contact ({worst_eq:.2e})")
    if worst_gap > 1e-9:
        fails.append(f"penetration outside the contact ({worst_gap:.2e})")

    # 3. The half-width scales with sqrt(q): 100 -> 200 N/mm changes it by a factor
    # sqrt(2); the contact must span clearly different cell counts, up and down.
    i_max = int(np.argmax(counts))
    if not (max(counts) - min(counts) >= 0.2 * max(counts) and
            min(counts[i_max:]) < max(counts) and min(counts[:i_max + 1]) < max(counts)):
        fails.append(f"contact did not grow and shrink: counts {counts}")

    # 4. Coulomb bound with the current pressure, to the run's relative tolerance (the
    # file's solver_rtol) of the largest bound.
    viol = np.max(np.abs(px) - mu * pn)
    rtol = float(ds.getncattr("solver_rtol"))
    print(f"max(|p_x| - mu p_n) = {viol:.3e} N/mm^2 (rtol {rtol:g})")
    if viol > rtol * mu * pn.max():
        fails.append(f"|p_x| exceeds mu p_n by {viol:.3g} N/mm^2")
    if ds.getncattr("status") != "complete":
        fails.append("status " + ds.getncattr("status"))
    for f in fails:
        print("FAIL:", f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
