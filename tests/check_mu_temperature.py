#!/usr/bin/env python3
"""mu(T), friction.temperature_table, in steady runs and sweeps (docs/model.md §18 "Couplings",
docs/verification.md 29).

  check_mu_temperature.py ROLLSIM CASE OUT_DIR      (CASE: cases/hot_creep_curve.yaml)

1. A constant table mu(T) = 0.3 with friction.mu = 0.4 is the case with friction.mu = 0.3 and no
   table: F_x of three points (partial slip, near saturation, full sliding) to 1e-9 relative
   (both are steady solves to Newton's tolerance, 1e-10 scaled; the factor 0.3/0.4 multiplies the
   bound instead of mu itself, so the two differ by round-off in the bound).
2. Full sliding (creepage -4 %, no cell in adhesion): |F_x| = sum mu_table(T1_i) p_n,i dx with T1
   the file's converged contact temperatures, the table interpolated here: an independent path
   from the output to the force. Tolerance 1e-8 relative: the fixed point stops when T changes
   by at most 1e-9 of the rise (mu moves by at most 1e-9 rise |dmu/dT| = 1.0e-10 here), Newton's
   tolerance, and the file's floats.
3. The fixed point, cell by cell: in every slipping cell |p_x| = mu_table(T1) p_n to 1e-8
   relative (the same budget as 2), and the file's mu is the table at T1 to the same tolerance.
   A velocity law keeps its shape: with the rational law mu_law = 0.3 + 0.1/(1 + |v_s|/500 mm/s)
   every slipping cell has |p| = mu_law(|v_s|) mu_T(T1)/mu_law(0) p_n (v_s = V slip from the file).
   The same in 3D: cases/ertz_temperature.yaml (full sliding at 1 m/s) with mu_T 0.3 at 0 degC
   to 0.15 at 300 degC, |p| = mu_T(T1) p_n in every contact cell.
4. The creep curve of the case: without the table (friction.mu = 0.4) it saturates, F_x/F_n at
   the largest creepage 0.4 to 1e-9 and never above; with the falling mu(T) it peaks inside the
   range and falls all the way after. The last point (full sliding) against an estimate: the
   coefficient is the p_n-weighted mean of mu(T) over the contact, and the flash temperature
   rises from the bulk temperature at the leading edge like the square root of the distance
   travelled (a heat flux roughly uniform in time), up to T_max at the trailing edge; under the
   semi-elliptic p_n the weighted mean of sqrt(s/2a) is (4/15)/(pi/8) = 0.679, so with mu
   linear in T the coefficient is mu(T_bulk + 0.679 (T_max - T_bulk)) to within the flux's
   non-uniformity (it grows with p_n): 0.01 allowed. The fall from the peak must exceed 0.03, two
   thirds of the fall that estimate gives for the case (peak 0.376, estimate 0.330).
"""
import os
import subprocess
import sys

import netCDF4
import numpy as np

from temperature_checks import Checks, run

check = Checks()
TABLE_T, TABLE_MU = [20.0, 400.0], [0.4, 0.2]


def mu_table(T):
    return np.interp(T, TABLE_T, TABLE_MU)


def main():
    rollsim, case, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    fields = ["--set", "output.fields=[px, pn, slip, regime]"]
    no_table = ["--set", "friction.temperature_table=null"]

    # 1. constant table = mu
    const = ["--set", "friction.temperature_table={temperature: [20, 400], mu: [0.3, 0.3]}"]
    for xi in (-0.005, -0.015, -0.05):
        pt = ["--set", f"rolling.creepage={xi}"]
        a = run(rollsim, ["run", case] + const + pt, os.path.join(out, "const.nc"))
        b = run(rollsim, ["run", case] + no_table + pt + ["--set", "friction.mu=0.3"],
                os.path.join(out, "plain.nc"))
        fa, fb = float(a["Fx"][-1]), float(b["Fx"][-1])
        rel = abs(fa - fb) / abs(fb)
        check(rel <= 1e-9, f"constant mu(T) = 0.3 as friction.mu = 0.3 at xi = {xi}", rel, "<= 1e-9")

    # 2., 3. full sliding
    d = run(rollsim, ["run", case, "--set", "rolling.creepage=-0.04"] + fields,
            os.path.join(out, "slide.nc"))
    px, pn, T1 = (np.asarray(d[v][-1], dtype=float) for v in ("px", "pn", "T1"))
    x = np.asarray(d["x"][:], dtype=float)
    dx = x[1] - x[0]
    check(int(d["n_adhesion"][-1]) == 0, "creepage -4 %: full sliding", int(d["n_adhesion"][-1]), 0)
    inside = pn > 0
    expect = np.sum(mu_table(T1[inside]) * pn[inside]) * dx
    got = abs(float(d["Fx"][-1]))
    rel = abs(got - expect) / abs(expect)
    check(rel <= 1e-8, f"|F_x| = sum mu(T1) p_n dx in full sliding ({got:.6g} N/mm, "
          f"T_max {float(d['T_max'][-1]):.1f} degC)", rel, "<= 1e-8")
    mu_used = mu_table(T1[inside])
    rel = np.max(np.abs(np.abs(px[inside]) - mu_used * pn[inside]) / (mu_used * pn[inside]))
    check(rel <= 1e-8, "every slipping cell at |p| = mu_table(T1) p_n", float(rel), "<= 1e-8")
    mu_file = np.asarray(d["mu"][-1], dtype=float)[inside]
    rel = np.max(np.abs(mu_file - mu_used) / mu_used)
    check(rel <= 1e-8, "the file's mu is the table at the file's T1", float(rel), "<= 1e-8")
    check(float(np.min(mu_used)) < 0.32, "the contact is hot enough to matter (min mu < 0.32)",
          float(np.min(mu_used)), "< 0.32")

    # a velocity law keeps its shape: rational mu_law = 0.3 + 0.1/(1 + |v_s|/500 mm/s) (0.4 at
    # rest) times mu_T(T)/0.4, in every slipping cell at xi = -2 % (v_s = V slip, V = 60 m/s)
    rat = ["--set", "friction.mu=null", "--set", "friction.law=rational", "--set",
           "friction.mu_kinetic=0.3", "--set", "friction.mu_excess=[0.1]", "--set",
           "friction.half_velocity=[500]", "--set", "rolling.creepage=-0.02", "--set",
           "output.fields=[px, pn, slip]"]
    dr = run(rollsim, ["run", case] + rat, os.path.join(out, "rational.nc"))
    pr, pnr, Tr = (np.asarray(dr[v][-1], dtype=float) for v in ("px", "pn", "T1"))
    vs = float(dr["velocity"][-1]) * np.abs(np.asarray(dr["slip"][-1], dtype=float))
    cr = (pnr > 0) & (vs > 0)
    mur = (0.3 + 0.1 / (1 + vs[cr] / 500.0)) * mu_table(Tr[cr]) / 0.4
    rel = np.max(np.abs(np.abs(pr[cr]) - mur * pnr[cr]) / (mur * pnr[cr]))
    check(rel <= 1e-8 and cr.sum() > 50, f"rational law times mu_T(T)/mu_law(0) in {int(cr.sum())} "
          "slipping cells", float(rel), "<= 1e-8")

    # 3D: Ertz & Knothe's contact in full sliding with mu_T 0.3 at 0 degC to 0.15 at 300 degC,
    # |p| = mu_T(T1) p_n in every contact cell (all slip), the same budget as in 2D
    ertz = os.path.join(os.path.dirname(case), "ertz_temperature.yaml")
    d3 = run(rollsim, ["run", ertz, "--set",
                       "friction.temperature_table={temperature: [0, 300], mu: [0.3, 0.15]}",
                       "--set", "output.fields=[px, pn]"], os.path.join(out, "ertz.nc"))
    pn3, T3 = (np.asarray(d3[v][-1], dtype=float) for v in ("pn", "T1"))
    p3 = np.hypot(np.asarray(d3["px"][-1], dtype=float), np.asarray(d3["py"][-1], dtype=float))
    c3 = pn3 > 0
    mu3 = np.interp(T3[c3], [0.0, 300.0], [0.3, 0.15])
    rel = np.max(np.abs(p3[c3] - mu3 * pn3[c3]) / (mu3 * pn3[c3]))
    check(rel <= 1e-8, f"3D full sliding: |p| = mu_T(T1) p_n in all {int(c3.sum())} contact cells "
          f"(T_max {float(d3['T_max'][-1]):.1f} degC)", float(rel), "<= 1e-8")

    # 4. the creep curve
    hot = run(rollsim, ["sweep", case], os.path.join(out, "hot.nc"))
    cold = run(rollsim, ["sweep", case] + no_table, os.path.join(out, "cold.nc"))
    fh = np.abs(np.asarray(hot["traction_coefficient"][:], dtype=float)).ravel()
    fc = np.abs(np.asarray(cold["traction_coefficient"][:], dtype=float)).ravel()
    check(abs(fc[-1] - 0.4) <= 1e-9 and np.max(fc) <= 0.4 * (1 + 1e-9),
          "without the table the curve saturates at mu = 0.4", float(fc[-1]), 0.4)
    peak = int(np.argmax(fh))
    check(0 < peak < len(fh) - 1, "with mu(T) the curve peaks inside the range",
          f"point {peak} of {len(fh)}", "interior")
    check(bool(np.all(np.diff(fh[peak:]) < 0)), "falling all the way from the peak",
          float(np.max(np.diff(fh[peak:]))), "< 0")
    tmax = float(np.asarray(hot["T_max"][:]).ravel()[-1])
    est = float(mu_table(TABLE_T[0] + 0.679 * (tmax - TABLE_T[0])))
    check(abs(fh[-1] - est) <= 0.01, f"last point (T_max {tmax:.1f} degC) against the p_n-weighted "
          f"mean of mu over a sqrt-rising temperature, {est:.4f}", float(fh[-1]), f"{est:.4f} +- 0.01")
    check(fh[peak] - fh[-1] > 0.03, f"falling branch: peak {fh[peak]:.4f}, last {fh[-1]:.4f}",
          float(fh[peak] - fh[-1]), "> 0.03")
    if check.failures:
        sys.exit(1)


if __name__ == "__main__":
    main()
