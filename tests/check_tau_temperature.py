#!/usr/bin/env python3
"""tau_c0(T), plasticity.tau_c0_table, in steady runs and sweeps (docs/model.md §18 "Couplings",
docs/verification.md 30).

  check_tau_temperature.py ROLLSIM CASE CASE3D OUT_DIR
      (CASE: cases/hot_creep_curve.yaml, CASE3D: cases/ertz_temperature.yaml)

The 2D case is the hot creep curve's contact (p0 = 1978 N/mm^2, V = 60 m/s) with Coulomb friction
mu = 0.4 (its mu(T) left out but in 4) and plasticity tau_c0 = 300 N/mm^2, so that most of the
contact flows plastically once it slides; the table lowers tau_c0 from 300 N/mm^2 at 20 degC to
150 N/mm^2 at 400 degC.

1. A constant table tau_c0(T) = 200 N/mm^2 with plasticity.tau_c0 = 300 is the case with
   plasticity.tau_c0 = 200 and no table (its floor 0.1 tau_c0 keeping its ratio): F_x at three
   creepages (partial slip, plastic flow, full sliding), hardening and softening, to 1e-9 relative
   (both steady solves to Newton's tolerance, 1e-10 scaled; the factor 2/3 scales the yield limit
   instead of tau_c0 itself, and the coupled run is warm-started several times).
2. Plastic flow (creepage -4 %, no cell in adhesion, hardening k_rel = 0.01): every flowing cell
   has |p_x| = tau_table(T1) + k_tau u* with T1 and u* from the file, the table interpolated here,
   to 1e-8 relative (the fixed point stops when T changes by at most 1e-9 of the rise, tau_c0
   moves by at most 1e-9 rise |dtau/dT| ~ 4e-8 N/mm^2 here, Newton's tolerance, and the file's
   floats); the file's tauc is the same to the same tolerance. F_x is the sum of these over the
   flowing cells plus mu p_n over the slipping ones, times dx, to 1e-8.
3. A hotter bulk temperature (20, 100, 200, 300, 450 degC for both bodies, perfectly plastic) lowers
   every flowing cell's yield limit and so the traction: |F_x| strictly falling; at 450 degC, above
   the table's last point, every flowing cell is at tau_c0 = 150 N/mm^2 and
   |F_x| = 150 (flowing length) + sum mu p_n dx over the slipping cells to 1e-8.
4. Both tables together (mu from 0.4 at 20 degC to 0.2 at 400 degC): in full sliding each contact
   cell carries |p| = min(mu_T(T1) p_n, tau_T(T1)) (slip where the bound is lower, flow where the
   yield limit is), to 1e-8.
5. 3D: Ertz & Knothe's contact in full sliding (1 m/s at 30 m/s, mu = 0.3) with tau_c0 from
   150 N/mm^2 at 0 degC to 100 N/mm^2 at 300 degC, perfectly plastic: every flowing cell at
   |p| = tau_T(T1), every slipping one at mu p_n, to 1e-8.
6. The creep curve (perfectly plastic): with the table it peaks inside the range and falls all the
   way after (the contact heats with the sliding speed, its yield limit falls), without it it does
   not fall; a sweep point, started from the last point's temperatures and state, is the single run
   started cold at its creepage to 1e-8 (two fixed points of tolerance 1e-9 of the rise).
"""
import os
import sys

import numpy as np

from temperature_checks import Checks, run

check = Checks()
G = 77519.4  # the case's shear modulus, N/mm^2
TAU_T, TAU_V = [20.0, 400.0], [300.0, 150.0]
TABLE = "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [300, 150]}"
PLAST, SLIP = 3, 2  # regime flags


def plastic(k_rel):
    return ["--set", f"plasticity={{tau_c0: 300, k_rel: {k_rel}}}"]


def arr(d, v):
    return np.asarray(d[v][-1], dtype=float)


def main():
    rollsim, case, case3, out = sys.argv[1:5]
    os.makedirs(out, exist_ok=True)
    base = ["run", case, "--set", "sweep=null", "--set", "friction.temperature_table=null"]
    fields = ["--set", "output.fields=[px, pn, ustar, tauc, regime]"]

    # 1. constant table = tau_c0
    const = ["--set", "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [200, 200]}"]
    for k_rel in (0.01, -0.02):
        for xi in (-0.002, -0.01, -0.04):
            pt = ["--set", f"rolling.creepage={xi}"]
            a = run(rollsim, base + plastic(k_rel) + const + pt, os.path.join(out, "const.nc"))
            b = run(rollsim, base + plastic(k_rel) + pt + ["--set", "plasticity.tau_c0=200"],
                    os.path.join(out, "plain.nc"))
            fa, fb = float(a["Fx"][-1]), float(b["Fx"][-1])
            rel = abs(fa - fb) / abs(fb)
            check(rel <= 1e-9, f"constant tau_c0(T) = 200 as plasticity.tau_c0 = 200, k_rel "
                  f"{k_rel}, xi = {xi} (F_x {fb:.6g} N/mm)", rel, "<= 1e-9")

    # 2. plastic flow with hardening
    k_rel = 0.01
    k_tau = G * k_rel / (1 - k_rel)
    d = run(rollsim, base + plastic(k_rel) + ["--set", TABLE, "--set", "rolling.creepage=-0.04"]
            + fields, os.path.join(out, "flow.nc"))
    px, pn, us, tauc, T1 = (arr(d, v) for v in ("px", "pn", "ustar", "tauc", "T1"))
    reg = arr(d, "regime").astype(int)
    dx = float(d["x"][1] - d["x"][0])
    flow, slip = reg == PLAST, reg == SLIP
    check(int(d["n_adhesion"][-1]) == 0 and flow.sum() > 50,
          "creepage -4 %: no adhesion, most cells flowing", int(flow.sum()), "> 50 of 100")
    want = np.interp(T1, TAU_T, TAU_V) + k_tau * us
    rel = np.max(np.abs(np.abs(px[flow]) - want[flow]) / want[flow])
    check(rel <= 1e-8, "every flowing cell at |p| = tau_table(T1) + k_tau u*", float(rel), "<= 1e-8")
    rel = np.max(np.abs(tauc[flow] - want[flow]) / want[flow])
    check(rel <= 1e-8, "the file's tauc is tau_table(T1) + k_tau u*", float(rel), "<= 1e-8")
    check(float(np.min(np.interp(T1[flow], TAU_T, TAU_V))) < 0.9 * 300,
          "hot enough to matter (tau_table(T1) below 270 N/mm^2 somewhere)",
          float(np.min(np.interp(T1[flow], TAU_T, TAU_V))), "< 270")
    expect = (np.sum(want[flow]) + np.sum(0.4 * pn[slip])) * dx
    rel = abs(abs(float(d["Fx"][-1])) - expect) / expect
    check(rel <= 1e-8, f"|F_x| = (sum tau_c(T1, u*) + sum mu p_n) dx ({expect:.6g} N/mm)", rel,
          "<= 1e-8")

    # 3. bulk temperature
    fx = []
    for bulk in (20, 100, 200, 300, 450):
        d = run(rollsim, base + plastic(0.0) + ["--set", TABLE, "--set", "rolling.creepage=-0.01",
                                                "--set", f"temperature.bulk={bulk}"] + fields,
                os.path.join(out, f"bulk{bulk}.nc"))
        fx.append(abs(float(d["Fx"][-1])))
    check(bool(np.all(np.diff(fx) < 0)), "hotter bulk, lower traction: |F_x| at 20, 100, 200, "
          "300, 450 degC strictly falling", [round(f, 4) for f in fx], "falling")
    pn, reg = arr(d, "pn"), arr(d, "regime").astype(int)
    flow, slip = reg == PLAST, reg == SLIP
    expect = (150.0 * flow.sum() + np.sum(0.4 * pn[slip])) * dx
    check(abs(fx[-1] - expect) <= 1e-8 * expect, "bulk 450 degC: |F_x| = (150 N/mm^2 flowing "
          f"length + sum mu p_n dx) ({expect:.6g} N/mm)", fx[-1], expect)

    # 4. both tables
    mu_tab = "friction.temperature_table={temperature: [20, 400], mu: [0.4, 0.2]}"
    d = run(rollsim, base + plastic(0.0) + ["--set", TABLE, "--set", mu_tab, "--set",
                                            "rolling.creepage=-0.04"] + fields,
            os.path.join(out, "both.nc"))
    px, pn, T1 = (arr(d, v) for v in ("px", "pn", "T1"))
    c = pn > 0
    want = np.minimum(np.interp(T1, [20.0, 400.0], [0.4, 0.2]) * pn, np.interp(T1, TAU_T, TAU_V))
    rel = np.max(np.abs(np.abs(px[c]) - want[c]) / want[c])
    check(rel <= 1e-8 and int(d["n_adhesion"][-1]) == 0, "mu(T) and tau_c0(T) together, full "
          "sliding: |p| = min(mu_T(T1) p_n, tau_T(T1)) in every contact cell", float(rel), "<= 1e-8")

    # 5. 3D
    d = run(rollsim, ["run", case3, "--set", "plasticity={tau_c0: 150, k_rel: 0.0}", "--set",
                      "plasticity.tau_c0_table={temperature: [0, 300], tau_c0: [150, 100]}",
                      "--set", "output.fields=[px, pn, regime]"], os.path.join(out, "ertz.nc"))
    pn, reg, T1 = arr(d, "pn"), arr(d, "regime").astype(int), arr(d, "T1")
    p = np.hypot(arr(d, "px"), arr(d, "py"))
    flow, slip = reg == PLAST, reg == SLIP
    want = np.where(flow, np.interp(T1, [0.0, 300.0], [150.0, 100.0]), 0.3 * pn)
    c = flow | slip
    rel = np.max(np.abs(p[c] - want[c]) / want[c])
    check(rel <= 1e-8 and flow.sum() > 100 and int(d["n_adhesion"][-1]) == 0,
          f"3D full sliding: |p| = tau_T(T1) in {int(flow.sum())} flowing cells, mu p_n in "
          f"{int(slip.sum())} slipping (T_max {float(d['T_max'][-1]):.1f} degC)", float(rel),
          "<= 1e-8")
    # 6. the creep curve
    sw = ["sweep", case, "--set", "friction.temperature_table=null"] + plastic(0.0)
    hot = run(rollsim, sw + ["--set", TABLE], os.path.join(out, "hot.nc"))
    cold = run(rollsim, sw, os.path.join(out, "cold.nc"))
    xs = np.asarray(hot["rolling_creepage"][:], dtype=float).ravel()
    fh = np.abs(np.asarray(hot["Fx"][:], dtype=float)).ravel()
    fc = np.abs(np.asarray(cold["Fx"][:], dtype=float)).ravel()
    peak = int(np.argmax(fh))
    check(0 < peak < len(fh) - 1 and bool(np.all(np.diff(fh[peak:]) < 0)),
          "with tau_c0(T) the plastic creep curve peaks inside the range and falls after",
          f"peak at point {peak} of {len(fh)}", "interior, falling")
    check(bool(np.all(np.diff(fc[peak:]) >= -1e-9 * fc[peak:-1])), "without the table it does not "
          "fall", float(np.min(np.diff(fc[peak:]))), ">= 0")
    for j in (10, 40):
        d = run(rollsim, base + plastic(0.0) + ["--set", TABLE, "--set",
                                                f"rolling.creepage={xs[j]}"],
                os.path.join(out, "point.nc"))
        rel = abs(abs(float(d["Fx"][-1])) - fh[j]) / fh[j]
        check(rel <= 1e-8, f"sweep point {j} (from the last point's temperatures) = the single run "
              f"from cold at xi = {xs[j]:.4g}", rel, "<= 1e-8")
    if check.failures:
        sys.exit(1)


if __name__ == "__main__":
    main()
