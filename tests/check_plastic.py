"""Checks on rollsim netCDF files with local plasticity (ctest, /usr/bin/python3).

regimes FILE RTOL
    The paper's regime conditions (eqs. 7-10) cell by cell in every record:
    E: p = 0;  H: |p| <= min(g, tau_c);  S: |p| = g <= tau_c;  P: |p| = tau_c < g,
    with g = mu p_n, to a tolerance of 20 rtol max(g) (the transient's interpolated
    output between steps carries errors of a few rtol; steady files pass rtol = 1e-9).
    Exception: a cell whose regime differs from that of the previous or the next
    record switched near this output time, and if the switch happened inside the IDA
    step the record was interpolated from, IDA's interpolating polynomial runs through
    the kink of p(t) and is off the new constraint by O(step x jump of dp/dt), which
    the error test does not bound (seen: p = 34.9956 for tau_c = 35.0001 in a cell
    that had just started to flow; the same file passes or fails with rtol 1e-6 or
    0.9e-6, whichever step falls on the switch). Such cells must still be admissible,
    |p| <= min(g, tau_c).
trends SWEEP.nc SATURATED.nc
    The paper's Figure-9 trends on a sweep over (plasticity.k_rel, rolling.creepage):
    F_x falls as k_rel falls at every creepage beyond the linear range; the k_rel = 0
    curve saturates at sum(min(mu p_n, tau_c0) dx)/F_n (p_n from SATURATED.nc, a run
    of the same case at k_rel = 0, xi = -0.02), to 1e-6; k_rel < 0 curves fall after
    their maximum; k_rel > 0 curves rise to the end and the stiffest is within 3 % of mu.
curves SWEEP.nc
    Every creep curve of a sweep whose last key is rolling.creepage (0 -> one sign) is
    free of jumps: |F_x| rises with |xi| for k_rel >= 0, and every curve (k_rel < 0 too)
    rises with a slope that never grows, i.e. its second differences are <= 1e-9 mu.
    Why: the slope of the creep curve is carried by the adhesion zone, which only shrinks
    as |xi| grows (Carter: 1 - (1 - |xi| R/(mu a))^2, concave); slip and plastic flow only
    cap cells. A step onto another solution branch shows as a slope that grows again
    (before the steady-plastic fix: second differences up to +1.6e-2 on cases/creep_curves.yaml).
"""
import sys

import netCDF4
import numpy as np
import yaml


def check(what, ok, detail=""):
    print(("ok  " if ok else "FAIL"), what, detail)
    if not ok:
        sys.exit(1)


def case_of(ds):
    return yaml.safe_load(ds.getncattr("case"))


def regimes(path, rtol):
    ds = netCDF4.Dataset(path)
    case = case_of(ds)
    mu = float(case.get("friction", {}).get("mu", 0.5))
    p = np.asarray(ds["px"][:])
    pn = np.asarray(ds["pn"][:])
    tauc = np.asarray(ds["tauc"][:])
    reg = np.asarray(ds["regime"][:])
    g = mu * pn
    tol = 20.0 * rtol * g.max()
    a = np.abs(p)
    switching = np.zeros(reg.shape, dtype=bool)
    switching[1:] |= reg[1:] != reg[:-1]
    switching[:-1] |= reg[:-1] != reg[1:]
    steady = ~switching
    bad = {
        "E: p = 0": (reg == 0) & (a != 0.0),
        "E: p_n = 0": (reg == 0) & (pn != 0.0),
        "H: |p| <= min(g, tau_c)": (reg == 1) & (a > np.minimum(g, tauc) + tol),
        "S: |p| = g": (reg == 2) & steady & (np.abs(a - g) > tol),
        "S: g <= tau_c": (reg == 2) & (g > tauc + tol),
        "P: |p| = tau_c": (reg == 3) & steady & (np.abs(a - tauc) > tol),
        "P: tau_c < g": (reg == 3) & (tauc > g + tol),
        "S, P switching: |p| <= min(g, tau_c)": (reg >= 2) & switching
        & (a > np.minimum(g, tauc) + tol),
    }
    counts = [int((reg == k).sum()) for k in range(4)]
    print(f"{path}: {p.shape[0]} records x {p.shape[1]} cells, E/H/S/P cell-records {counts}, "
          f"{int(((reg >= 2) & switching).sum())} S/P cell-records at a regime switch, tol {tol:.3g} N/mm2")
    for what, mask in bad.items():
        n = int(mask.sum())
        detail = ""
        if n:
            r, i = np.argwhere(mask)[0]
            detail = f"({n} violations, first record {r} cell {i}: p {p[r, i]:.6g} g {g[r, i]:.6g} tau_c {tauc[r, i]:.6g})"
        check(what, n == 0, detail)
    check("every regime occurs (a plastic case passes through all four)", all(c > 0 for c in counts))


def trends(sweep_path, sat_path):
    ds = netCDF4.Dataset(sweep_path)
    k = np.asarray(ds["plasticity_k_rel"][:])
    xi = np.asarray(ds["rolling_creepage"][:])
    tc = np.asarray(ds["traction_coefficient"][:])  # [k, xi]
    conv = np.asarray(ds["converged"][:])
    check("every sweep point converged", bool((conv == 1).all()))
    mu = float(case_of(ds)["friction"]["mu"])
    order = np.argsort(-k)  # k_rel falling
    beyond_linear = np.abs(xi) >= 0.002
    diffs = np.diff(tc[order][:, beyond_linear], axis=0)
    check("F_x falls as k_rel falls (|xi| >= 0.2 %)", bool((diffs < 0).all()), f"(max step {diffs.max():.3g})")

    sat = netCDF4.Dataset(sat_path)
    scase = case_of(sat)
    tau_c0 = float(scase["plasticity"]["tau_c0"])
    pn = np.asarray(sat["pn"][-1])
    x = np.asarray(sat["x"][:])
    dx = x[1] - x[0]
    bound = np.sum(np.minimum(mu * pn, tau_c0)) * dx / (np.sum(pn) * dx)
    i0 = int(np.argmin(np.abs(k - 0.0)))
    check("k_rel = 0 saturates at sum min(mu p_n, tau_c0) dx / F_n",
          abs(abs(tc[i0, -1]) - bound) <= 1e-6 * bound, f"({abs(tc[i0, -1]):.8f} vs {bound:.8f})")
    for i in np.where(k < 0)[0]:
        curve = np.abs(tc[i])
        imax = int(np.argmax(curve))
        check(f"k_rel = {k[i]:g} falls after its maximum", imax < len(curve) - 1 and curve[-1] < curve[imax],
              f"(max {curve[imax]:.5f} at xi = {xi[imax]:g}, end {curve[-1]:.5f})")
    for i in np.where(k > 0)[0]:
        curve = np.abs(tc[i])
        check(f"k_rel = {k[i]:g} still rises at the end", curve[-1] > curve[-2])
    istiff = int(np.argmax(k))
    check(f"k_rel = {k[istiff]:g} reaches within 3 % of mu at |xi| = {abs(xi[-1]):g}",
          abs(tc[istiff, -1]) >= 0.97 * mu, f"({abs(tc[istiff, -1]):.5f})")


def curves(sweep_path):
    ds = netCDF4.Dataset(sweep_path)
    dims = list(ds["traction_coefficient"].dimensions)  # the swept keys (profiles add x)
    check("the last sweep key is rolling.creepage", ds[dims[-1]].getncattr("key") == "rolling.creepage")
    check("every sweep point converged", bool((np.asarray(ds["converged"][:]) == 1).all()))
    mu = float(case_of(ds)["friction"]["mu"])
    xi = np.asarray(ds[dims[-1]][:])
    check("creepages of one sign, in order of |xi|",
          bool((np.diff(np.abs(xi)) > 0).all() and (xi <= 0).all() or (xi >= 0).all()))
    tc = np.abs(np.asarray(ds["traction_coefficient"][:])).reshape(-1, len(xi))
    shape = [len(ds[d]) for d in dims[:-1]]
    k_axis = dims.index("plasticity_k_rel") if "plasticity_k_rel" in dims else None
    for flat, curve in enumerate(tc):
        idx = np.unravel_index(flat, shape) if shape else ()
        label = ", ".join(f"{ds[d].getncattr('key')} = {float(ds[d][i]):g}" for d, i in zip(dims[:-1], idx))
        k_rel = float(ds["plasticity_k_rel"][idx[k_axis]]) if k_axis is not None else 1.0
        d1 = np.diff(curve)
        d2 = np.diff(d1)
        if k_rel >= 0:
            check(f"{label}: rises with |xi|", bool((d1 >= -1e-12).all()), f"(min step {d1.min():.3g})")
        check(f"{label}: slope never grows (no jump)", bool((d2 <= 1e-9 * mu).all()),
              f"(largest second difference {d2.max():.3g} at xi = {xi[int(np.argmax(d2)) + 1]:g})")


if __name__ == "__main__":
    if sys.argv[1] == "regimes":
        regimes(sys.argv[2], float(sys.argv[3]))
    elif sys.argv[1] == "trends":
        trends(sys.argv[2], sys.argv[3])
    elif sys.argv[1] == "curves":
        curves(sys.argv[2])
    else:
        sys.exit(f"unknown check {sys.argv[1]}")
