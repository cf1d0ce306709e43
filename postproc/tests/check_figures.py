#!/usr/bin/python3
"""The paper's figures as make_figures.sh draws them: the series behind every panel (the CSV
the plot commands write with --data, recorded as each series is drawn) against the values in
the sweep files the figures come from (netCDF4, read here independently of rollsim_post).

  check_figures.py DATADIR ELASTIC8.nc ELASTIC9.nc

DATADIR holds fig7/fig8/fig9 .nc and .csv (make_figures.sh ROLLSIM OUT DATADIR).
ELASTIC8.nc / ELASTIC9.nc: the Meierhofer / creep-curve sweeps over the creepage run without a
plasticity: block, i.e. the purely elastic model: the series the figures label "elastic"
(tau_c0 = 1e9 N/mm2, never reached) must equal them to the Newton tolerance.

Checks, per figure:
  7  one panel per k_rel (0.98, 0.6, 0, -0.333), each with p_x, g = mu p_n and tau_c of that
     point: x, p_x, tau_c bit for bit, g = 0.5 p_n to 1 ulp; the regime shading is not data.
  8  one panel per creepage (-0.3 %, -1 %), each overlaying tau_c0 = 200 (p_x, tau_c) and the
     elastic point (p_x only, labelled elastic), g once; values as for 7.
  9  one panel per plastic tau_c0 (200, 250, 350; none for 1e9), in each one series per k_rel
     (x = 100 |xi|, y = |F_x/F_n| bit for bit) and the elastic series (tau_c0 = 1e9).
"""
import sys
from collections import defaultdict

import netCDF4
import numpy as np

from check_drawn import read_csv  # the --data CSV, one group per (panel, series, quantity)

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok  " if ok else "FAIL"), what, detail)
    failures += not ok


def index_of(ds, dim, value):
    coord = np.asarray(ds[dim][:])
    i = np.nonzero(coord == value)[0]
    assert i.size == 1, (dim, value, coord)
    return int(i[0])


def figure7(ds, groups):
    x = np.asarray(ds["x"][:])
    k = np.asarray(ds["plasticity_k_rel"][:])
    panels = defaultdict(dict)
    for (panel, series, quantity), g in groups.items():
        panels[panel][quantity] = g
    check("fig 7: one panel per k_rel", len(panels) == k.size, f"({len(panels)} panels)")
    for panel, q in sorted(panels.items()):
        kv = q["px"]["point"]["plasticity.k_rel"]
        i = index_of(ds, "plasticity_k_rel", kv)
        check(f"fig 7 panel {panel} ({q['px']['title']}): quantities p_x, g, tau_c",
              set(q) == {"px", "g", "tau_c"}, str(sorted(q)))
        check(f"fig 7 k_rel = {kv:g}: x is the file's x", all(np.array_equal(g["x"], x) for g in q.values()))
        check(f"fig 7 k_rel = {kv:g}: p_x bit for bit", np.array_equal(q["px"]["y"], ds["px"][i, :]))
        check(f"fig 7 k_rel = {kv:g}: tau_c bit for bit", np.array_equal(q["tau_c"]["y"], ds["tauc"][i, :]))
        g_ref = 0.5 * np.asarray(ds["pn"][i, :])
        check(f"fig 7 k_rel = {kv:g}: g = mu p_n (mu = 0.5)",
              np.allclose(q["g"]["y"], g_ref, rtol=2.3e-16, atol=0.0))


def figure8(ds, groups, elastic):
    x = np.asarray(ds["x"][:])
    panels = defaultdict(dict)
    for (panel, series, quantity), g in groups.items():
        panels[panel][(series, quantity)] = g
    check("fig 8: one panel per creepage", len(panels) == len(ds["rolling_creepage"]))
    for panel, q in sorted(panels.items()):
        names = sorted(q)
        want = [("g = μ p_n", "g"), ("p_x, elastic", "px"), ("p_x, τ_c0 = 200 N/mm²", "px"),
                ("τ_c, τ_c0 = 200 N/mm²", "tau_c")]
        check(f"fig 8 panel {panel}: elastic and tau_c0 = 200 overlaid, g once, no tau_c for elastic",
              names == sorted(want), str(names))
        if names != sorted(want):
            continue
        plastic = q[("p_x, τ_c0 = 200 N/mm²", "px")]
        xi = plastic["point"]["rolling.creepage"]
        c = index_of(ds, "rolling_creepage", xi)
        t200 = index_of(ds, "plasticity_tau_c0", 200.0)
        t_el = index_of(ds, "plasticity_tau_c0", q[("p_x, elastic", "px")]["point"]["plasticity.tau_c0"])
        check(f"fig 8 xi = {xi:g}: x is the file's x", all(np.array_equal(g["x"], x) for g in q.values()))
        check(f"fig 8 xi = {xi:g}: plastic p_x bit for bit", np.array_equal(plastic["y"], ds["px"][t200, c, :]))
        check(f"fig 8 xi = {xi:g}: tau_c bit for bit",
              np.array_equal(q[("τ_c, τ_c0 = 200 N/mm²", "tau_c")]["y"], ds["tauc"][t200, c, :]))
        el = q[("p_x, elastic", "px")]["y"]
        check(f"fig 8 xi = {xi:g}: elastic p_x bit for bit", np.array_equal(el, ds["px"][t_el, c, :]))
        check(f"fig 8 xi = {xi:g}: g = 0.5 p_n",
              np.allclose(q[("g = μ p_n", "g")]["y"], 0.5 * np.asarray(ds["pn"][t200, c, :]), rtol=2.3e-16, atol=0))
        # Independent: the purely elastic model (no plasticity block) at this creepage.
        e = index_of(elastic, "rolling_creepage", xi)
        ref = np.asarray(elastic["px"][e, :])
        dev = np.max(np.abs(el - ref)) / np.max(np.abs(ref))
        check(f"fig 8 xi = {xi:g}: 'elastic' equals the elastic model", dev <= 1e-6, f"(max dev {dev:.2e} of max |p_x|, tol 1e-6)")


def figure9(ds, groups, elastic):
    xi = np.asarray(ds["rolling_creepage"][:])
    tau = np.asarray(ds["plasticity_tau_c0"][:])
    k_rel = np.asarray(ds["plasticity_k_rel"][:])
    tc = np.asarray(ds["traction_coefficient"][:])
    panels = defaultdict(dict)
    for (panel, series, quantity), g in groups.items():
        if quantity == "traction_coefficient":
            panels[panel][series] = g
    titles = sorted({g["title"] for p in panels.values() for g in p.values()})
    check("fig 9: one panel per plastic tau_c0 (200, 250, 350), none for 1e9",
          titles == ["τ_c0 = 200 N/mm²", "τ_c0 = 250 N/mm²", "τ_c0 = 350 N/mm²"], str(titles))
    e_ref = np.abs(np.asarray(elastic["traction_coefficient"][:]))
    for panel, series in sorted(panels.items()):
        labels = sorted(series)
        want = sorted([f"k_rel = {k:g}" for k in k_rel] + ["elastic"])
        check(f"fig 9 panel {panel}: one series per k_rel and the elastic one", labels == want, str(labels))
        for label, g in series.items():
            p = g["point"]
            t = index_of(ds, "plasticity_tau_c0", p["plasticity.tau_c0"])
            k = index_of(ds, "plasticity_k_rel", p["plasticity.k_rel"])
            check(f"fig 9 panel {panel} {label}: x = 100 |xi| (in %)", np.array_equal(g["x"], 100.0 * np.abs(xi)))
            check(f"fig 9 panel {panel} {label}: y = |F_x/F_n| bit for bit", np.array_equal(g["y"], np.abs(tc[t, k, :])))
            if label == "elastic":
                check(f"fig 9 panel {panel}: the elastic series has tau_c0 = 1e9", tau[t] == 1e9)
                dev = np.max(np.abs(g["y"] - e_ref))
                check(f"fig 9 panel {panel}: 'elastic' equals the elastic model", dev <= 1e-6 * 0.5,
                      f"(max dev {dev:.2e}, tol 5e-7 = 1e-6 mu)")
            else:
                check(f"fig 9 panel {panel} {label}: plastic tau_c0 in the panel title",
                      g["title"] == f"τ_c0 = {tau[t]:g} N/mm²")


def main():
    data, el8, el9 = sys.argv[1:4]
    figure7(netCDF4.Dataset(f"{data}/fig7.nc"), read_csv(f"{data}/fig7.csv"))
    figure8(netCDF4.Dataset(f"{data}/fig8.nc"), read_csv(f"{data}/fig8.csv"), netCDF4.Dataset(el8))
    figure9(netCDF4.Dataset(f"{data}/fig9.nc"), read_csv(f"{data}/fig9.csv"), netCDF4.Dataset(el9))
    print(f"{failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
