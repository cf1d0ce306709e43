#!/usr/bin/python3
"""Numeric checks of rollsim_post's extraction code (the functions the figures and the CSV use).

Usage:
  check_postproc.py export   RUN.nc WORKDIR        CSV written by the CLI == netCDF values
  check_postproc.py nearest  RUN.nc                --time picks the nearest stored record
  check_postproc.py bound    RUN.nc MU             g = mu p_n with mu from the case attribute
  check_postproc.py creep    FILE...               series grouping, labels and sorting
  check_postproc.py sweep    FIXTURE_DIR           sweep-file reader on the synthetic files
  check_postproc.py rig      RUN.nc                twin-disc step/revolution means vs records
  check_postproc.py history  RUN.nc OUTDIR         history --data: every drawn series == the file's
  check_postproc.py readme   README.md             the README's command table lists every subcommand
  check_postproc.py sweep_views DATA_DIR OUTDIR    regimes/plastic/traction of rollsim sweep files
                                                   (fig7.nc, fig8.nc): the series each draws (--data)
                                                   == the profiles of the points they name

Each check prints what it compares and exits 1 on the first failure.
"""
import csv
import os
import subprocess
import sys

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
POSTPROC = os.path.dirname(HERE)
sys.path.insert(0, POSTPROC)
sys.path.insert(0, HERE)

from rollsim_post import PostError, extract  # noqa: E402
from rollsim_post.runfile import RunFile  # noqa: E402

CLI = [sys.executable, os.path.join(POSTPROC, "rollsim_post.py")]


def fail(msg):
    print(f"FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def nc_values(path, name):
    with netCDF4.Dataset(path) as ds:
        return np.ma.getdata(ds.variables[name][...]).astype(np.float64)


# ---- export --------------------------------------------------------------------------------

def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def run_export(path, names, out):
    proc = subprocess.run(CLI + ["export", path, "--var", *names, "--csv", out],
                          capture_output=True, text=True)
    check(proc.returncode == 0, f"export exited {proc.returncode}: {proc.stderr.strip()}")


def check_export(path, workdir):
    os.makedirs(workdir, exist_ok=True)
    with netCDF4.Dataset(path) as ds:
        nt, nx = len(ds.dimensions["time"]), len(ds.dimensions["x"])

    # Tolerance: none. The CSV holds repr(double), the shortest decimal string that reads back to
    # the identical IEEE double, so float(cell) must equal the stored value bit for bit.
    scalars = ["Fx", "Fn", "traction_coefficient", "creepage", "n_slip", "plastic_power"]
    out = os.path.join(workdir, "pp_export_scalars.csv")
    run_export(path, scalars, out)
    header, rows = read_csv(out)
    check(header == ["time"] + scalars, f"scalar header {header}")
    check(len(rows) == nt, f"{len(rows)} rows for {nt} records")
    for j, name in enumerate(["time"] + scalars):
        got = np.array([float(r[j]) for r in rows])
        want = nc_values(path, name)
        check(np.array_equal(got, want),
              f"{name}: max |CSV - netCDF| = {np.max(np.abs(got - want))}")
    print(f"export scalars: {nt} records x {len(scalars)} variables identical")

    fields = ["px", "slip", "regime"]
    out = os.path.join(workdir, "pp_export_fields.csv")
    run_export(path, fields, out)
    header, rows = read_csv(out)
    check(header == ["time", "x"] + fields, f"field header {header}")
    check(len(rows) == nt * nx, f"{len(rows)} rows for {nt} x {nx} (long format)")
    got = np.array([[float(c) for c in r] for r in rows])
    t, x = nc_values(path, "time"), nc_values(path, "x")
    # Long format, x fastest: row k is record k // nx, cell k % nx.
    check(np.array_equal(got[:, 0], np.repeat(t, nx)), "time column of the long format")
    check(np.array_equal(got[:, 1], np.tile(x, nt)), "x column of the long format")
    for j, name in enumerate(fields):
        want = nc_values(path, name).reshape(-1)
        check(np.array_equal(got[:, 2 + j], want),
              f"{name}: max |CSV - netCDF| = {np.max(np.abs(got[:, 2 + j] - want))}")
    regime_cells = [r[4] for r in rows[:nx]]
    check(all(c.lstrip("-").isdigit() for c in regime_cells), "regime (byte) written as integers")
    print(f"export fields: {nt * nx} rows (long format) identical for {', '.join(fields)}")


# ---- nearest record ------------------------------------------------------------------------

def check_nearest(path):
    with RunFile(path) as run:
        t = run.values("time")
        n = t.size
        check(n >= 4, f"need at least 4 records, got {n}")
        k = n // 2
        dt = t[k + 1] - t[k]
        cases = [
            (t[k] + 0.3 * dt, k, "30 % of the way from record k to k+1"),
            (t[k] + 0.7 * dt, k + 1, "70 % of the way from record k to k+1"),
            (0.5 * (t[k] + t[k + 1]), k, "exact midpoint: the earlier record"),
            (t[k], k, "exactly on record k"),
            (t[0] - 1.0, 0, "before the first record"),
            (t[-1] + 1.0, n - 1, "after the last record"),
            # rollsim always stores the end time, so the last interval may be shorter.
            (t[-2] + 0.6 * (t[-1] - t[-2]), n - 1, "60 % into the last (short) interval"),
        ]
        requested = [c[0] for c in cases]
        got = extract.record_indices(run, requested)
        for (treq, want, what), idx in zip(cases, got):
            check(idx == want, f"time {treq!r} ({what}): record {idx}, expected {want}")
        check(extract.record_indices(run, None) == [n - 1], "default record is the last")
        # The profile of the chosen record is that record's p_x, bit for bit (no interpolation).
        prof = extract.traction_profile(run, got[0])
        check(np.array_equal(prof.px, nc_values(path, "px")[k]), "profile p_x is record k's")
        check(prof.time == t[k], "profile time is record k's")
    print(f"nearest record: {len(cases)} requested times map to the expected records "
          f"(k = {k}, t_k = {t[k]!r}, dt = {dt!r})")


# ---- traction bound ------------------------------------------------------------------------

def check_bound(path, mu_expected):
    with RunFile(path) as run:
        mu = run.mu()
        # mu is parsed from the YAML text: it must be the case's number exactly.
        check(mu == float(mu_expected), f"mu from the case attribute {mu}, expected {mu_expected}")
        prof = extract.traction_profile(run, run.n_records() - 1)
        values, meanings = run.regime_flags()
        slip_code = values[meanings.index("slip")]
    g_max = np.max(prof.g)
    # In slip cells Coulomb's law holds with equality, |p_x| = g = mu p_n. rollsim solves it to
    # rtol = 1e-6 of the traction scale; stored records are interpolated (IDA dense output), where
    # the bound is met to a few rtol (3.6e-6 g_max seen on default.yaml). Tolerance 1e-5 g_max:
    # 10 rtol. A wrong mu (e.g. the default 0.5 instead of 0.3) would miss by ~40 % of g.
    tol = 1e-5 * g_max
    slip = prof.regime == slip_code
    check(np.count_nonzero(slip) > 0, "no slip cells at the last record")
    err = np.max(np.abs(np.abs(prof.px[slip]) - prof.g[slip]))
    check(err <= tol, f"slip cells: max ||p_x| - mu p_n| = {err} > {tol}")
    over = np.max(np.abs(prof.px) - prof.g)
    check(over <= tol, f"|p_x| exceeds g = mu p_n by {over} > {tol}")
    check(np.array_equal(prof.g, mu * nc_values(path, "pn")[-1]), "g is mu * p_n")
    print(f"bound: mu = {mu}; slip cells |p_x| = g to {err:.3g} N/mm2 (tol {tol:.3g}); "
          f"|p_x| <= g + {over:.3g}")


# ---- creep curves from single-run files ----------------------------------------------------

def expected_points(paths):
    """Independent of rollsim_post: (title, creepage, traction coefficient) of the last record."""
    points = []
    for p in paths:
        with netCDF4.Dataset(p) as ds:
            points.append((ds.title, float(ds.variables["creepage"][-1]),
                           float(ds.variables["traction_coefficient"][-1])))
    return points


def check_creep(paths):
    pts = expected_points(paths)
    titles = list(dict.fromkeys(p[0] for p in pts))  # order of first appearance
    check(len(titles) >= 2, f"need files of at least two series, got titles {titles}")

    # Default: series by title, in order of first appearance, points sorted by creepage.
    # Exact comparison: the points are copied from the file, not computed.
    series = extract.creep_series(paths)
    check([s.label for s in series] == titles, f"series {[s.label for s in series]} != {titles}")
    for s in series:
        want = sorted((c, f) for t, c, f in pts if t == s.label)
        check(list(zip(s.creepage, s.traction)) == want, f"series {s.label!r}: points {want}")
        check(np.all(np.diff(s.creepage) > 0), f"series {s.label!r}: creepage not ascending")
        check(len(s.sources) == len(want), f"series {s.label!r}: one source per point")
    print(f"creep: {len(series)} series by title, "
          + "; ".join(f"{s.label!r}: {s.creepage.size} points" for s in series))

    # Reversed input order changes the order of the series but not their content.
    rev = extract.creep_series(list(reversed(paths)))
    check([s.label for s in rev] == list(dict.fromkeys(p[0] for p in reversed(pts))),
          "reversed files: series order follows the first file of each series")
    for s in rev:
        ref = next(r for r in series if r.label == s.label)
        check(np.array_equal(s.creepage, ref.creepage) and np.array_equal(s.traction, ref.traction),
              f"reversed files: series {s.label!r} differs")

    # --group-by friction.mu: labels from the case, series sorted by the numeric value.
    grouped = extract.creep_series(list(reversed(paths)), group_by="friction.mu")
    labels = [s.label for s in grouped]
    mus = [float(lab.split("=")[1]) for lab in labels]
    check(all(lab.startswith("friction.mu = ") for lab in labels), f"group-by labels {labels}")
    check(mus == sorted(mus), f"group-by series not sorted by mu: {labels}")
    check(sum(s.creepage.size for s in grouped) == len(paths), "group-by keeps every point")

    # One --label for all files: a single series of every point, sorted.
    one = extract.creep_series(paths, labels=["all"])
    check(len(one) == 1 and one[0].creepage.size == len(paths), "one --label: one series")
    check(np.all(np.diff(one[0].creepage) >= 0), "one --label: sorted by creepage")
    try:
        extract.creep_series(paths, labels=["a", "b"] if len(paths) != 2 else ["a", "b", "c"])
        fail("a wrong number of --label values was accepted")
    except PostError:
        pass
    print(f"creep: reversed order, --group-by friction.mu {labels}, single --label checked")


# ---- sweep files ---------------------------------------------------------------------------

def check_sweep(fixture_dir):
    import make_fixtures as mf

    path = os.path.join(fixture_dir, "sweep_krel_creep.nc")
    with RunFile(path) as run:
        check(run.is_sweep(), "sweep file not recognised as a sweep")
        series = extract.sweep_series(run)
    # One series per k_rel, in the file's coordinate order; labels use the dotted key.
    labels = [s.label for s in series]
    want_labels = [f"plasticity.k_rel = {k:g}" for k in mf.K_REL]
    check(labels == want_labels, f"labels {labels} != {want_labels}")
    creep_sorted = sorted(mf.CREEPAGE)
    for i, (k, s) in enumerate(zip(mf.K_REL, series)):
        creep = [c for j, c in enumerate(mf.CREEPAGE) if (i, j) != mf.MISSING]
        want_c = np.array(sorted(creep))
        # Exact: the file stores the doubles traction() returned; the reader only reorders them.
        want_f = np.array([mf.traction(c, k) for c in want_c])
        check(np.array_equal(s.creepage, want_c), f"k_rel = {k}: creepage {s.creepage}")
        check(np.array_equal(s.traction, want_f), f"k_rel = {k}: traction {s.traction}")
    check(series[mf.MISSING[0]].creepage.size == len(creep_sorted) - 1,
          "the missing (fill value) point is dropped")
    print(f"sweep {os.path.basename(path)}: {len(series)} series, creepage ascending, "
          "missing point dropped, values exact")

    path = os.path.join(fixture_dir, "sweep_creep_tau.nc")
    with RunFile(path) as run:
        series = extract.sweep_series(run)
    check([s.label for s in series] == [f"plasticity.tau_c0 = {t:g}" for t in mf.TAU_C0],
          f"labels {[s.label for s in series]}")
    for t, s in zip(mf.TAU_C0, series):
        want_c = np.array(sorted(mf.CREEPAGE_B))
        want_f = np.array([mf.traction(c, 0.0, t) for c in want_c])
        check(np.array_equal(s.creepage, want_c), f"tau_c0 = {t}: creepage {s.creepage}")
        check(np.array_equal(s.traction, want_f), f"tau_c0 = {t}: traction {s.traction}")
    print(f"sweep {os.path.basename(path)}: creepage as the first dimension, values exact")

    # Through creep_series with a label prefix, mixed with the other sweep file.
    mixed = extract.creep_series([os.path.join(fixture_dir, "sweep_creep_tau.nc"),
                                  os.path.join(fixture_dir, "sweep_krel_creep.nc")],
                                 labels=["B", "A"])
    check([s.label for s in mixed][:2] == [f"B: plasticity.tau_c0 = {t:g}" for t in mf.TAU_C0]
          and len(mixed) == len(mf.TAU_C0) + len(mf.K_REL), "labels prefix sweep series")
    print("sweep: creep_series keeps file order and prefixes labels")


# ---- twin disc -----------------------------------------------------------------------------

def trapezoid_mean(t, f, a, b):
    """Mean of the piecewise-linear interpolant of (t, f) over [a, b]."""
    grid = np.concatenate(([a], t[(t > a) & (t < b)], [b]))
    vals = np.interp(grid, t, f)
    return float(np.sum(0.5 * (vals[1:] + vals[:-1]) * np.diff(grid)) / (b - a))


def check_rig(path):
    """The means rollsim integrates over its time steps agree with the means of the stored
    records (every T/20) over the same windows: to 2 % of the largest traction coefficient
    (records sample the first revolution's build-up coarsely: measured at most 0.9 %, in revolution 1), and the step
    slips are the held values exactly (a step's window ends where the next slip begins)."""
    with RunFile(path) as run:
        rig = extract.rig_results(run)
        t, mu = run.values("time"), run.values("traction_coefficient")
        w0, w1 = run.values("step_window_start"), run.values("step_time_end")
        slip_end = run.values("step_slip_end")
        T = float(run.attr("twin_disc_revolution_time"))
    check(len(rig.step_mu) == 2, f"expected 2 completed steps, got {len(rig.step_mu)}")
    scale = np.max(np.abs(rig.rev_mu))
    for j in range(2):
        ref = trapezoid_mean(t, mu, w0[j], w1[j])
        print(f"step {j + 1}: slip {rig.step_slip[j]:.6g} (held {slip_end[j]:.6g}), "
              f"mu {rig.step_mu[j]:.6f}, records {ref:.6f}")
        check(abs(rig.step_slip[j] - slip_end[j]) <= 1e-12, "step slip is not the held slip")
        check(abs(rig.step_mu[j] - ref) <= 0.02 * scale, "step mean differs from the records")
    for k, mk in zip(rig.rev_index, rig.rev_mu):
        ref = trapezoid_mean(t, mu, (k - 1) * T, min(k * T, t[-1]))
        print(f"revolution {k}: mu {mk:.6f}, records {ref:.6f}")
        check(abs(mk - ref) <= 0.02 * scale, "revolution mean differs from the records")
    check(len(rig.rev_mu) == 6, f"expected 6 revolutions, got {len(rig.rev_mu)}")


def plotted(args, out_png, out_csv):
    """Run a figure command with --data; the recorded rows grouped by (panel, series, quantity)."""
    proc = subprocess.run(CLI + args + ["-o", out_png, "--data", out_csv], capture_output=True, text=True)
    check(proc.returncode == 0, f"{' '.join(args)}: exit {proc.returncode}: {proc.stderr}")
    groups = {}
    with open(out_csv) as f:
        r = csv.reader(f)
        head = next(r)
        keys = head[4:-2]
        for row in r:
            key = (int(row[0]), row[2], row[3])
            g = groups.setdefault(key, {"title": row[1], "x": [], "y": [],
                                        "point": {k: float(v) for k, v in zip(keys, row[4:-2]) if v}})
            g["x"].append(float(row[-2]))
            g["y"].append(float(row[-1]))
    return groups


def check_history(path, out):
    os.makedirs(out, exist_ok=True)
    groups = plotted(["history", path], f"{out}/history.png", f"{out}/history.csv")
    names = ["traction_coefficient", "creepage", "velocity", "n_exterior", "n_adhesion", "n_slip",
             "n_plastic", "frictional_power", "plastic_power"]
    drawn = {q: g["y"] for (_, _, q), g in groups.items()}
    check(sorted(drawn) == sorted(names), f"history draws {sorted(drawn)}")
    for name in names:
        check(np.array_equal(np.array(drawn[name]), nc_values(path, name)),
              f"history {name}: drawn != file")
    print(f"OK: history of {path}: {len(names)} series, {len(drawn['creepage'])} records each, "
          "== the file")


def point_index(ds, point):
    """Index tuple of a sweep point (coordinates compared exactly: the CSV holds repr())."""
    idx = []
    for d in ds["traction_coefficient"].dimensions:
        coord = np.asarray(ds[d][:])
        hits = np.nonzero(coord == point[ds[d].key])[0]
        check(hits.size == 1, f"{d} = {point.get(ds[d].key)} not a coordinate value")
        idx.append(int(hits[0]))
    return tuple(idx)


def check_sweep_views(data, out):
    os.makedirs(out, exist_ok=True)
    f7, f8 = netCDF4.Dataset(os.path.join(data, "fig7.nc")), netCDF4.Dataset(os.path.join(data, "fig8.nc"))
    x = np.asarray(f7["x"][:])
    # regimes: rows along the last swept key (creepage), one panel per tau_c0.
    g = plotted(["regimes", os.path.join(data, "fig8.nc")], f"{out}/reg8.png", f"{out}/reg8.csv")
    check(len({p for p, _, _ in g}) == 2 and len(g) == 4, f"regimes fig8: {sorted(g)}")
    for (panel, series, quantity), row in g.items():
        i = point_index(f8, row["point"])
        check(quantity == "regime" and np.array_equal(row["y"], np.asarray(f8["regime"][i], float)),
              f"regimes fig8 {series}: regime row != file")
        check(("elastic" in series) == (row["point"]["plasticity.tau_c0"] == 1e9),
              f"regimes fig8 {series}: 'elastic' must mark exactly tau_c0 = 1e9")
    # plastic, overlaid along k_rel: one panel pair, u* and tau_c of every k_rel.
    g = plotted(["plastic", os.path.join(data, "fig7.nc"), "--overlay", "plasticity.k_rel"],
                f"{out}/pl7.png", f"{out}/pl7.csv")
    check(len(g) == 8, f"plastic fig7: {sorted(g)}")
    for (panel, series, quantity), row in g.items():
        i = point_index(f7, row["point"])
        var = {"ustar": "ustar", "tau_c": "tauc"}[quantity]
        check(np.array_equal(row["x"], x) and np.array_equal(row["y"], np.asarray(f7[var][i])),
              f"plastic fig7 {series} {quantity} != file")
    # traction --select: the one point asked for.
    g = plotted(["traction", os.path.join(data, "fig8.nc"), "--select", "rolling.creepage=-0.0100001",
                 "--select", "plasticity.tau_c0=190"], f"{out}/sel.png", f"{out}/sel.csv")
    pts = {tuple(sorted(r["point"].items())) for r in g.values()}
    check(pts == {(("plasticity.tau_c0", 200.0), ("rolling.creepage", -0.01))},
          f"--select picked {pts}, want the nearest point tau_c0 = 200, xi = -0.01")
    px = next(r for (p, s, q), r in g.items() if q == "px")
    check(np.array_equal(px["y"], np.asarray(f8["px"][point_index(f8, px["point"])])), "--select: p_x != file")
    print(f"OK: sweep regimes, plastic overlay and --select draw the file's profiles ({data})")


def check_readme(path):
    from rollsim_post import cli
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    text = open(path).read()
    table = set(__import__("re").findall(r"^\| `([a-z0-9]+) ", text, __import__("re").M))
    missing = sorted(set(sub.choices) - table)
    check(not missing, f"{path}: subcommands missing from the table: {missing}")
    extra = sorted(table - set(sub.choices))
    check(not extra, f"{path}: the table names commands that do not exist: {extra}")
    print(f"OK: {path} lists every subcommand: {', '.join(sorted(sub.choices))}")


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    cmd, args = argv[1], argv[2:]
    if cmd == "export" and len(args) == 2:
        check_export(*args)
    elif cmd == "nearest" and len(args) == 1:
        check_nearest(*args)
    elif cmd == "bound" and len(args) == 2:
        check_bound(*args)
    elif cmd == "creep" and len(args) >= 2:
        check_creep(args)
    elif cmd == "sweep" and len(args) == 1:
        check_sweep(*args)
    elif cmd == "rig" and len(args) == 1:
        check_rig(*args)
    elif cmd == "history" and len(args) == 2:
        check_history(*args)
    elif cmd == "readme" and len(args) == 1:
        check_readme(*args)
    elif cmd == "sweep_views" and len(args) == 2:
        check_sweep_views(*args)
    else:
        sys.exit(__doc__)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
