#!/usr/bin/python3
"""What the 2D figures of rollsim runs draw (the CSV of `rollsim_post.py ... --data`) against the
netCDF files they come from, read here with netCDF4 only (not through rollsim_post).

  check_drawn.py traction RUN.nc CSV MU [T ...]  panels at the records nearest T (default: last);
                                                 p_x (and tau_c) equal the file's, g = MU p_n
  check_drawn.py regimes RUN.nc CSV              the x-t map: every (record, cell) drawn, its
                                                 regime code (-1 where not stored)
  check_drawn.py plastic RUN.nc CSV              the two x-t maps u* and tau_c
  check_drawn.py creep CSV RUN.nc ...            one series per title (coefficient of friction),
                                                 each file's (creepage, F_x/F_n) in it once
  check_drawn.py rig RUN.nc CSV                  per step: (100 slip, coefficient) of the steps
                                                 done; per revolution: coefficient and 100 slip
  check_drawn.py friction3d RUN.nc CSV           3D friction figure: the mu map = the file's
                                                 contact cells; the scatter = (|v_s|, mu) of
                                                 every cell, |v_s| = V |slip|; each cell on the
                                                 case's law (recomputed here from the case text)

Values are compared bit for bit where the figure draws the stored number itself, and to 1 ulp
where it draws a product (g = mu p_n, 100 slip). Exit status 1 on any failure.
"""
import csv
import sys

import netCDF4
import numpy as np

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok  " if ok else "FAIL"), what, detail)
    failures += not ok


def read_csv(path):
    """{(panel, series, quantity): dict(title, point, x, y, value)} in drawing order."""
    groups = {}
    with open(path) as f:
        r = csv.reader(f)
        head = next(r)
        maps = head[-1] == "value"
        nv = 3 if maps else 2
        keys = head[4:-nv]
        for row in r:
            panel, title, series, quantity = int(row[0]), row[1], row[2], row[3]
            point = {k: float(v) for k, v in zip(keys, row[4:-nv]) if v != ""}
            g = groups.setdefault((panel, series, quantity),
                                  dict(title=title, point=point, x=[], y=[], value=[]))
            g["x"].append(float(row[-nv]))
            g["y"].append(float(row[-nv + 1]))
            if maps:
                g["value"].append(float(row[-1]) if row[-1] != "" else np.nan)
    for g in groups.values():
        for k in ("x", "y", "value"):
            g[k] = np.array(g[k])
    return groups


def var(ds, name):
    return np.ma.filled(np.ma.asarray(ds[name][:], dtype=np.float64), np.nan)


def same(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and bool(np.all((a == b) | (np.isnan(a) & np.isnan(b))))


def within_ulp(a, b):
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= np.spacing(np.abs(b)) + 0.0))


def max_diff(a, b):
    d = np.abs(np.asarray(a, dtype=np.float64) - np.asarray(b, dtype=np.float64))
    return f"(max |diff| {np.nanmax(d) if d.size else 0:.3g})"


def traction(path, csv_path, mu, times):
    groups = read_csv(csv_path)
    with netCDF4.Dataset(path) as ds:
        t, x = var(ds, "time"), var(ds, "x")
        px, pn = var(ds, "px"), var(ds, "pn")
        tauc = var(ds, "tauc") if "tauc" in ds.variables else None
    wanted = [int(np.argmin(np.abs(t - s))) for s in times] or [t.size - 1]
    panels = sorted({p for p, _, _ in groups})
    check("one panel per requested time", len(panels) == len(wanted), f"{len(panels)}")
    for k, i in zip(panels, wanted):
        got = groups[(k, "p_x", "px")]
        check(f"panel {k}: the record nearest the requested time (t = {t[i]:.6g} s)",
              got["point"].get("time") == t[i], f"{got['point']}")
        check(f"panel {k}: x = the cell centres", same(got["x"], x))
        check(f"panel {k}: p_x = the file's record {i}", same(got["y"], px[i]),
              max_diff(got["y"], px[i]))
        g = [v for (p, s, q), v in groups.items() if p == k and q == "g"]
        check(f"panel {k}: g = {mu} p_n (1 ulp)", len(g) == 1 and within_ulp(g[0]["y"], mu * pn[i]),
              max_diff(g[0]["y"], mu * pn[i]) if g else "no g")
        gm = [v for (p, s, q), v in groups.items() if p == k and q == "-g"]
        check(f"panel {k}: -g drawn", len(gm) == 1 and same(gm[0]["y"], -g[0]["y"]))
        tc = [v for (p, s, q), v in groups.items() if p == k and q == "tau_c"]
        if tauc is None:
            check(f"panel {k}: no tau_c without a tauc field", not tc)
        else:
            sign = -1.0 if np.nansum(px[i]) < 0 else 1.0
            check(f"panel {k}: tau_c on the side of the net traction ({sign:+g})",
                  len(tc) == 1 and same(tc[0]["y"], sign * tauc[i]))


def xt_map(groups, panel, name, x, t, values):
    got = [v for (p, s, q), v in groups.items() if p == panel and q == name]
    check(f"{name}: one map in panel {panel}", len(got) == 1)
    if not got:
        return
    g = got[0]
    X, T = np.meshgrid(x, t)
    check(f"{name}: every cell of every record drawn ({values.size})", g["x"].size == values.size)
    if g["x"].size != values.size:
        return
    check(f"{name}: x = the cell centres", same(g["x"], X.ravel()))
    ratio = g["y"][T.ravel() != 0] / T.ravel()[T.ravel() != 0]
    unit_ok = ratio.size > 0 and np.allclose(ratio, ratio[0], rtol=1e-15, atol=0) and \
        any(abs(ratio[0] / f - 1) < 1e-15 for f in (1.0, 1e3, 1e6))
    check(f"{name}: time axis = the record times in s, ms or µs", unit_ok)
    check(f"{name}: the values = the file's", same(g["value"], values.ravel()),
          max_diff(g["value"], values.ravel()))


def regimes(path, csv_path):
    groups = read_csv(csv_path)
    with netCDF4.Dataset(path) as ds:
        t, x, reg = var(ds, "time"), var(ds, "x"), var(ds, "regime")
    xt_map(groups, 0, "regime", x, t, np.where(np.isnan(reg), -1.0, reg))
    check("records with a plastic cell drawn as such (code 3)",
          np.any(reg == 3) == any(np.any(g["value"] == 3) for g in groups.values()))


def plastic(path, csv_path):
    groups = read_csv(csv_path)
    with netCDF4.Dataset(path) as ds:
        t, x = var(ds, "time"), var(ds, "x")
        ustar, tauc = var(ds, "ustar"), var(ds, "tauc")
    check("u* grows somewhere (a plastic run)", np.nanmax(ustar) > 0)
    xt_map(groups, 0, "ustar", x, t, ustar)
    xt_map(groups, 1, "tauc", x, t, tauc)


def creep(csv_path, paths):
    groups = read_csv(csv_path)
    series = {s: v for (p, s, q), v in groups.items()}
    expected = {}
    for path in paths:
        with netCDF4.Dataset(path) as ds:
            expected.setdefault(ds.title, []).append(
                (float(var(ds, "creepage")[-1]), float(var(ds, "traction_coefficient")[-1])))
    check("one series per title", len(series) == len(expected), f"{sorted(series)}")
    for title, pts in expected.items():
        match = [s for s in series if s in title or title in s]
        check(f"series of '{title}'", len(match) == 1, f"{match}")
        if len(match) != 1:
            continue
        g = series[match[0]]
        pts.sort()
        check(f"'{title}': the {len(pts)} points of its files, sorted by creepage",
              same(g["x"], [p[0] for p in pts]) and same(g["y"], [p[1] for p in pts]))


def rig(path, csv_path):
    groups = read_csv(csv_path)
    with netCDF4.Dataset(path) as ds:
        s_slip, s_mu = var(ds, "step_slip"), var(ds, "step_traction_coefficient")
        r_slip, r_mu = var(ds, "revolution_slip"), var(ds, "revolution_traction_coefficient")
    done, rdone = np.isfinite(s_mu), np.isfinite(r_mu)
    step = groups.get((0, "step", "traction_coefficient"))
    check("per step: the steps done", step is not None and same(step["y"], s_mu[done]),
          f"{int(done.sum())} of {s_mu.size}")
    if step is not None:
        check("per step: slip in % (1 ulp)", within_ulp(step["x"], 100.0 * s_slip[done]))
    rev = groups.get((1, "revolution", "traction_coefficient"))
    idx = np.nonzero(rdone)[0] + 1.0
    check("per revolution: coefficient of every revolution done",
          rev is not None and same(rev["x"], idx) and same(rev["y"], r_mu[rdone]),
          f"{int(rdone.sum())} revolutions")
    sl = groups.get((1, "revolution", "slip_percent"))
    check("per revolution: slip in % (1 ulp)",
          sl is not None and same(sl["x"], idx) and within_ulp(sl["y"], 100.0 * r_slip[rdone]))
    # with a temperature: block, the third panel: each temperature per revolution as stored
    series = {"revolution_T_max": "largest in the contact",
              "revolution_inlet_temperature_1": "entering the contact: disc 1",
              "revolution_inlet_temperature_2": "entering the contact: disc 2",
              "revolution_bulk_temperature_1": "bulk: disc 1",
              "revolution_bulk_temperature_2": "bulk: disc 2"}
    with netCDF4.Dataset(path) as ds:
        stored = {n: var(ds, n) for n in series if n in ds.variables}
    for name, values in stored.items():
        got = groups.get((2, series[name], "temperature_degC"))
        check(f"per revolution: {name}", got is not None and same(got["x"], idx)
              and same(got["y"], values[rdone]), f"{int(rdone.sum())} revolutions")


def law_of(case_text):
    """mu(|v_s|) of the case's exponential, linear or rational law (docs/case-file.md)."""
    import yaml
    fr = yaml.safe_load(case_text)["friction"]
    mk, ex, vh = fr["mu_kinetic"], fr["mu_excess"], fr["half_velocity"]
    ex, vh = (ex if isinstance(ex, list) else [ex]), (vh if isinstance(vh, list) else [vh])

    def mu(s):
        out = mk + 0.0 * s
        for i, (d, v) in enumerate(zip(ex, vh)):
            if fr["law"] == "exponential":
                out = out + d * np.exp(-np.log(2.0) * s / v)
            elif fr["law"] == "linear":
                out = out + d * np.maximum(0.0, 1.0 - s / (2.0 * v))
            else:
                out = out + (d / (1.0 + s / v) if i == 0 else d / (1.0 + (s / v) ** 2))
        return out
    return mu


def friction3d(path, csv_path):
    groups = read_csv(csv_path)
    with netCDF4.Dataset(path) as ds:
        x, y, V = var(ds, "x"), var(ds, "y"), float(var(ds, "velocity")[-1])
        mu = var(ds, "mu")[-1]
        speed = V * np.hypot(var(ds, "slip_x")[-1], var(ds, "slip_y")[-1])
        law = law_of(ds.getncattr("case"))
    inside = np.isfinite(mu)
    X, Y = np.meshgrid(x, y)
    m = groups.get((0, "mu", "mu"))
    check("map: the contact cells (finite mu) at their centres",
          m is not None and same(m["x"], X[inside]) and same(m["y"], Y[inside]),
          f"{int(inside.sum())} cells")
    check("map: mu = the file's (bit for bit)", m is not None and same(m["value"], mu[inside]))
    c = groups.get((1, "cells", "mu"))
    check("scatter: mu of every contact cell", c is not None and same(c["y"], mu[inside]))
    check("scatter: |v_s| = V |(slip_x, slip_y)| (1e-12)", c is not None and
          np.allclose(c["x"], speed[inside], rtol=1e-12, atol=0.0))
    check("partial slip: slip speeds from 0 to over 50 mm/s",
          speed[inside].min() < 1e-6 and speed[inside].max() > 50.0,
          f"{speed[inside].min():.3g} .. {speed[inside].max():.3g} mm/s")
    dev = np.abs(mu[inside] - law(speed[inside])).max()
    # a steady state: every cell's bound is mu(|v_s|) p_n; Newton's tolerance on v_s
    # (<= 1e-3 mm/s) moves mu by at most |mu'| 1e-3 = 7e-7
    check("every cell on the law: max |mu - mu_law(|v_s|)| <= 1e-6", dev <= 1e-6, f"{dev:.2e}")


def main(argv):
    what = argv[1] if len(argv) > 1 else ""
    if what == "traction" and len(argv) >= 5:
        traction(argv[2], argv[3], float(argv[4]), [float(a) for a in argv[5:]])
    elif what in ("regimes", "plastic", "rig", "friction3d") and len(argv) == 4:
        {"regimes": regimes, "plastic": plastic, "rig": rig,
         "friction3d": friction3d}[what](argv[2], argv[3])
    elif what == "creep" and len(argv) >= 4:
        creep(argv[2], argv[3:])
    else:
        sys.exit(__doc__)
    print("FAILED" if failures else "all ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
