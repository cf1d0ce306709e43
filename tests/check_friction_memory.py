"""Checks of friction memory (issue 14, docs/model.md §11) on cases/friction_memory.yaml (ctest,
/usr/bin/python3). Every expectation comes from the equations or from an independent run
(the memoryless law, the Coulomb law, the steady solver, an uninterrupted run), never from
a stored result. The same checks serve the 3D case tests/cases/friction_memory_3d.yaml: there
the tractions are (px, py) and the force (F_x, F_y).

relax RUN.nc CASE.yaml
    After the creepage step the contact slides fully at 0.6 to 1.6 m/s, where the law is
    mu_k to 1e-3 dmu (v_h = 50 mm/s): each particle enters at mu(0) and d_c dmu/ds = -(mu - mu_k) along
    its sliding distance s = integral of |slip| dx from the leading edge, so
    ln(mu - mu_k) is linear in s with slope -1/d_c. Fitted on the contact cells of the last
    record; d_c within 3 %: the first-order upwind transport makes the decay per cell
    1/(1 + h) instead of exp(-h), h = |slip| dx/d_c ~ 0.02, a bias of h/2 ~ 1 %.
limit SWEEP.nc
    Steady rolling at partial slip over friction.memory_distance = [0, d, d/10, d/100,
    d/1000]: the memoryless law at 0. At a fixed grid the discrete memory equation gives
    mu - mu_law = O(d_c), so the differences |F(d_c) - F(0)| (F_x; in 3D |(F_x, F_y)|) fall by 10 per decade of
    d_c: each ratio within 10 +- 1.5 (the O(d_c^2) remainder), and the smallest below
    1e-6 F_n.
near SWEEP.nc TOL_F TOL_P
    The same at 400 cells (the steady solver's Newton-Krylov path with the near-field
    preconditioner, memory rows included) for d_c = 1e-9 mm: F_x equals the memoryless
    law's to TOL_F F_n (1e-6; measured 6e-9) and px to TOL_P of max |px| (2e-4): the first
    slipping cell after an adhering one lags the law by (mu_up - mu_law)/(1 + h), h =
    |slip| dx/d_c ~ 2000 there, i.e. ~1.5e-5 in mu, 3e-5 of its traction.
steady TRANSIENT.nc STEADY.nc
    The transient from rest (kept at its final creepage until it settles) against the
    steady solver at that creepage: F_x (and F_y), p and mu within 1e-4 (of F_x, max |p|,
    mu(0)).
restart FULL.nc CONTINUED.nc
    A run stopped halfway and continued with --restart against the uninterrupted run: the
    last records agree (px, mu, F_x) to the run's tolerance (global attribute solver_rtol,
    at least 1e-6) relative: the integrator restarts at order 1 from the stored state, and two
    integrations of one problem under the same error control differ by about their tolerance.
coulomb MEMORY.nc COULOMB.nc
    A half velocity far above every slip speed (1e12 mm/s) makes the law constant,
    mu = mu_k + dmu: with memory the state stays there and the run equals the Coulomb
    run with that mu (px, F_x to 1e-8 relative; mu = mu_k + dmu to 1e-8 in every cell).
"""
import math
import sys

import netCDF4
import numpy as np
import yaml

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok  " if ok else "FAIL"), what, detail)
    if not ok:
        failures += 1


def last(path):
    ds = netCDF4.Dataset(path)
    out = {k: np.array(ds[k][-1]) for k in ("px", "py", "pn", "slip", "mu") if k in ds.variables}
    out["x"] = np.array(ds["x"][:])
    out["Fx"] = float(ds["Fx"][-1])
    if "Fy" in ds.variables:  # 3D
        out["Fy"] = float(ds["Fy"][-1])
    out["time"] = float(ds["time"][-1])
    ds.close()
    return out


def relax(run_path, case_path):
    case = yaml.safe_load(open(case_path))
    fr = case["friction"]
    d_c, mu_k = fr["memory_distance"], fr["mu_kinetic"]
    r = last(run_path)
    x, mu, slip, pn = r["x"], r["mu"], r["slip"], r["pn"]
    dx = x[1] - x[0]
    contact = pn > 0
    speed = np.abs(slip[contact]) * case["rolling"]["velocity"]
    print(f"  slip speeds {speed.min():.4g} to {speed.max():.4g} mm/s")
    check("full sliding after the step at slip speeds > 10 v_h (the law is mu_k to 1e-3 dmu)",
          np.all(speed > 10 * fr["half_velocity"][0]))
    # sliding distance of the particle in cell i since it entered (material enters at high x)
    s = np.cumsum((np.abs(slip) * dx)[::-1])[::-1]
    idx = np.where(contact)[0]
    idx = idx[1:-1]  # the edge cells see the jump of p_n
    y = np.log(mu[idx] - mu_k)
    slope, icpt = np.polyfit(s[idx], y, 1)
    fit = -1.0 / slope
    resid = np.max(np.abs(y - (slope * s[idx] + icpt)))
    print(f"  relaxation over {s[idx].max() - s[idx].min():.4g} mm of sliding, "
          f"{len(idx)} cells: fitted distance {fit:.6g} mm, d_c {d_c} mm, "
          f"log residual {resid:.3g}")
    check("fitted relaxation distance within 3 % of d_c", abs(fit / d_c - 1) < 0.03,
          f"({fit / d_c - 1:+.4f})")
    check("exponential: ln(mu - mu_k) linear in s to 0.02", resid < 0.02)
    check("mu at the leading edge is near mu(0) (fresh material)",
          abs(mu[idx[-1]] - (mu_k + fr["mu_excess"][0])) < 0.05 * fr["mu_excess"][0])


def limit(sweep_path):
    ds = netCDF4.Dataset(sweep_path)
    dc = np.array(ds["friction_memory_distance"][:]).ravel()
    fx = np.array(ds["Fx"][:]).ravel()
    fn = np.array(ds["Fn"][:]).ravel()
    # 3D: the tangential force (F_x, F_y); 2D: F_x
    fy = np.array(ds["Fy"][:]).ravel() if "Fy" in ds.variables else np.zeros_like(fx)
    ds.close()
    order = np.argsort(-dc)
    dc, fx, fy = dc[order], fx[order], fy[order]
    ref, ref_y = fx[dc == 0][0], fy[dc == 0][0]
    mem = dc > 0
    diffs = np.hypot(fx[mem] - ref, fy[mem] - ref_y)
    for d, f, e in zip(dc[mem], fx[mem], diffs):
        print(f"  d_c = {d:.3g} mm: F_x = {f:.12g}, |F - F(no memory)| = {e:.4g}")
    ratios = diffs[:-1] / diffs[1:]
    print("  ratios of successive differences:", " ".join(f"{q:.4g}" for q in ratios))
    check("first order in d_c: every ratio within 10 +- 1.5",
          np.all(np.abs(ratios - 10) < 1.5))
    check("smallest d_c within 1e-6 F_n of the memoryless law", diffs[-1] < 1e-6 * fn[0])


def near(sweep_path, tol, tol_p):
    ds = netCDF4.Dataset(sweep_path)
    dc = np.array(ds["friction_memory_distance"][:]).ravel()
    fx = np.array(ds["Fx"][:]).ravel()
    fn = np.array(ds["Fn"][:]).ravel()
    px = np.array(ds["px"][:])
    ds.close()
    ref = np.where(dc == 0)[0][0]
    for k in np.where(dc > 0)[0]:
        dfx = abs(fx[k] - fx[ref]) / fn[ref]
        dp = np.max(np.abs(px[k] - px[ref])) / np.max(np.abs(px[ref]))
        print(f"  d_c = {dc[k]:.3g} mm: |F_x - F_x(no memory)| = {dfx:.3g} F_n, px {dp:.3g}")
        check(f"d_c = {dc[k]:.3g} mm: F_x equals the memoryless law's to {tol:g} F_n", dfx < tol)
        check(f"d_c = {dc[k]:.3g} mm: px equals the memoryless law's to {tol_p:g} of max |px|",
              dp < tol_p)


def traction_diff(a, b):
    """max |p_a - p_b| over the cells and components (px, and py in 3D) / max |p_b|."""
    comps = [k for k in ("px", "py") if k in b]
    scale = max(np.max(np.abs(b[k])) for k in comps)
    return max(np.max(np.abs(a[k] - b[k])) for k in comps) / scale


def steady(tr_path, st_path):
    a, b = last(tr_path), last(st_path)
    dp = traction_diff(a, b)
    in_c = b["pn"] > 0
    dmu = np.max(np.abs(a["mu"][in_c] - b["mu"][in_c]))
    dfx = abs(a["Fx"] - b["Fx"]) / abs(b["Fx"])
    print(f"  transient at t = {a['time']:.6g} s against steady: F_x {a['Fx']:.10g} / "
          f"{b['Fx']:.10g} (rel {dfx:.3g}), p {dp:.3g} of max |p|, mu {dmu:.3g}")
    check("transient from rest reaches the steady state: F_x to 1e-4", dfx < 1e-4)
    if "Fy" in b:
        dfy = abs(a["Fy"] - b["Fy"]) / abs(b["Fy"])
        print(f"  F_y {a['Fy']:.10g} / {b['Fy']:.10g} (rel {dfy:.3g})")
        check("F_y to 1e-4", dfy < 1e-4)
    check("p to 1e-4 of max |p|", dp < 1e-4)
    check("mu to 1e-4 in the contact", dmu < 1e-4)


def restart(full_path, cont_path):
    a, b = last(full_path), last(cont_path)
    check("same final time", abs(a["time"] - b["time"]) < 1e-15)
    dp = traction_diff(b, a)
    dmu = np.max(np.abs(a["mu"] - b["mu"]))
    dfx = abs(a["Fx"] - b["Fx"]) / abs(a["Fx"])
    print(f"  restarted against uninterrupted: p {dp:.3g} of max |p|, mu {dmu:.3g}, "
          f"F_x rel {dfx:.3g}")
    with netCDF4.Dataset(full_path) as d:
        tol = max(1e-6, float(d.getncattr("solver_rtol")))
    check(f"restart halfway equals the uninterrupted run to {tol:.3g}", max(dp, dmu, dfx) < tol)


def coulomb(mem_path, coul_path, mu_total):
    a, b = last(mem_path), last(coul_path)
    scale = np.max(np.abs(b["px"]))
    dp = np.max(np.abs(a["px"] - b["px"])) / scale
    dfx = abs(a["Fx"] - b["Fx"]) / abs(b["Fx"])
    dmu = np.max(np.abs(a["mu"] - mu_total))
    print(f"  memory with v_h = 1e12 mm/s against Coulomb mu = {mu_total}: px {dp:.3g} of "
          f"max |px|, F_x rel {dfx:.3g}, |mu - mu_k - dmu| {dmu:.3g}")
    check("Coulomb limit with memory: px to 1e-8", dp < 1e-8)
    check("F_x to 1e-8", dfx < 1e-8)
    check("the state stays at mu_k + dmu to 1e-8", dmu < 1e-8)


def main(argv):
    what = argv[1]
    if what == "relax":
        relax(argv[2], argv[3])
    elif what == "limit":
        limit(argv[2])
    elif what == "near":
        near(argv[2], float(argv[3]), float(argv[4]))
    elif what == "steady":
        steady(argv[2], argv[3])
    elif what == "restart":
        restart(argv[2], argv[3])
    elif what == "coulomb":
        coulomb(argv[2], argv[3], float(argv[4]))
    else:
        raise SystemExit(f"unknown check {what}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
