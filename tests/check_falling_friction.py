"""Checks of cases/falling_friction.yaml (ctest, /usr/bin/python3): velocity-dependent
friction, elastic and plastic creep curves side by side.

sweep SWEEP.nc CASE.yaml
    The sweep over (plasticity.tau_c0 = [1e9 (elastic), 200], rolling.creepage 0 -> -2 %):
    - elastic, xi = -2 %: every contact cell slips and F_x/F_n lies between mu at the
      largest and at the smallest slip speed |v_s| = |slip| V of the patch (the law is
      evaluated here from the case's keys, not by rollsim); the curve falls: its end is
      below its maximum by more than 5 % (mu(0) = 0.5 against mu(600 mm/s) = 0.325); the
      stored field mu equals the law at every contact cell (1e-9);
    - plastic: every point at most the yield bound tau_c0 sum_{p_n > 0} dx / F_n (|p| <=
      tau_c0 in every contact cell) to 1e-9, and below the elastic curve beyond xi = 0.
run RUN.nc CASE.yaml
    A run of the case: the field mu equals the law at |v_s| = |slip| V in every slipping
    cell (1e-9), mu(0) in adhesion (1e-9), NaN outside the contact.
run3d RUN.nc CASE.yaml
    A 3D steady run (tests/cases/falling_friction_3d.yaml): the field mu is on (time, y, x)
    and equals the law at |v_s| = |(slip_x, slip_y)| V in every slipping cell (1e-9), mu(0)
    in adhesion (1e-9), NaN outside the contact; the slipping cells carry
    |p| = mu p_n (1e-9 of max p_n).
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


def law(fr, s):
    s = np.abs(s)
    name = fr["law"]
    if name == "polach":
        return fr["mu_static"] * ((1 - fr["A"]) * np.exp(-fr["B"] * s) + fr["A"])
    ex, vh = fr["mu_excess"], fr["half_velocity"]
    ex = ex if isinstance(ex, list) else [ex]
    vh = vh if isinstance(vh, list) else [vh]
    mu = fr["mu_kinetic"] + 0 * s
    for i, (d, v) in enumerate(zip(ex, vh)):
        if name == "exponential":
            mu = mu + d * np.exp(-math.log(2) * s / v)
        elif name == "linear":
            mu = mu + d * np.maximum(0, 1 - s / (2 * v))
        elif i == 0:
            mu = mu + d / (1 + s / v)
        else:
            mu = mu + d / (1 + (s / v) ** 2)
    return mu


def sweep(path, case_path):
    case = yaml.safe_load(open(case_path))
    fr, V = case["friction"], case["rolling"]["velocity"]
    ds = netCDF4.Dataset(path)
    taus = ds["plasticity_tau_c0"][:]
    xi = ds["rolling_creepage"][:]
    tc = ds["traction_coefficient"][:]
    x = ds["x"][:]
    dx = x[1] - x[0]
    e = int(np.argmax(taus))
    p = 1 - e
    slip, pn, reg = ds["slip"][e, -1, :], ds["pn"][e, -1, :], ds["regime"][e, -1, :]
    inside = pn > 0
    check("elastic, xi = %g: every contact cell slips" % xi[-1], np.all(reg[inside] == 2))
    mus = law(fr, slip[inside] * V)
    check("elastic, xi = %g: F_x/F_n = %.5f within mu over the patch [%.5f, %.5f]"
          % (xi[-1], tc[e, -1], mus.min(), mus.max()),
          mus.min() - 1e-9 <= abs(tc[e, -1]) <= mus.max() + 1e-9)
    mu_field = ds["mu"][e, -1, :].filled(np.nan)
    check("elastic, xi = %g: stored mu = law(|v_s|) in every contact cell" % xi[-1],
          np.max(np.abs(mu_field[inside] - mus)) <= 1e-9)
    peak = np.max(np.abs(tc[e]))
    check("elastic curve falls: end %.5f < 0.95 max %.5f" % (abs(tc[e, -1]), peak),
          abs(tc[e, -1]) < 0.95 * peak)
    tau = taus[p]
    worst = 0.0
    for k in range(len(xi)):
        pnk = ds["pn"][p, k, :]
        bound = tau * dx * np.sum(pnk > 0) / (np.sum(pnk) * dx)
        worst = max(worst, abs(tc[p, k]) - bound)
    check("plastic: F_x/F_n <= tau_c0 (contact length) / F_n", worst <= 1e-9, "excess %.3g" % worst)
    check("plastic below elastic beyond xi = 0",
          np.all(np.abs(tc[p, 1:]) < np.abs(tc[e, 1:])))


def run(path, case_path):
    case = yaml.safe_load(open(case_path))
    fr, V = case["friction"], case["rolling"]["velocity"]
    ds = netCDF4.Dataset(path)
    mu, slip = ds["mu"][-1, :].filled(np.nan), ds["slip"][-1, :]
    pn, reg = ds["pn"][-1, :], ds["regime"][-1, :]
    s = reg == 2
    check("mu field = law(|v_s|) in the %d slipping cells" % np.sum(s),
          np.sum(s) > 0 and np.max(np.abs(mu[s] - law(fr, slip[s] * V))) <= 1e-9)
    h = reg == 1
    check("mu field = mu(0) in the %d adhesion cells" % np.sum(h),
          np.all(np.abs(mu[h] - law(fr, 0.0)) <= 1e-9))
    check("mu field NaN outside the contact", np.all(np.isnan(mu[pn <= 0])) and np.sum(pn <= 0) > 0)


def run3d(path, case_path):
    case = yaml.safe_load(open(case_path))
    fr, V = case["friction"], case["rolling"]["velocity"]
    ds = netCDF4.Dataset(path)
    check("mu on (time, y, x)", ds["mu"].dimensions == ("time", "y", "x"),
          str(ds["mu"].dimensions))
    mu = ds["mu"][-1].filled(np.nan)
    speed = np.hypot(ds["slip_x"][-1], ds["slip_y"][-1]) * V
    p = np.hypot(ds["px"][-1], ds["py"][-1])
    pn, reg = ds["pn"][-1], ds["regime"][-1]
    s, h = reg == 2, reg == 1
    check("mu field = law(|v_s|) in the %d slipping cells" % np.sum(s),
          np.sum(s) > 0 and np.max(np.abs(mu[s] - law(fr, speed[s]))) <= 1e-9)
    check("|p| = law(|v_s|) p_n in the slipping cells",
          np.max(np.abs(p[s] - law(fr, speed[s]) * pn[s])) <= 1e-9 * np.max(pn))
    check("mu field = mu(0) in the %d adhesion cells" % np.sum(h),
          np.sum(h) > 0 and np.all(np.abs(mu[h] - law(fr, 0.0)) <= 1e-9))
    check("mu field NaN outside the contact", np.all(np.isnan(mu[pn <= 0])) and np.sum(pn <= 0) > 0)


if __name__ == "__main__":
    {"sweep": sweep, "run": run, "run3d": run3d}[sys.argv[1]](sys.argv[2], sys.argv[3])
    sys.exit(1 if failures else 0)
