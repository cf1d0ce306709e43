#!/usr/bin/python3
"""Numbers drawn by the 3D figures (--data) against the analytic content of the synthetic files
(make_fixtures3d.py) and against real rollsim 3D output.

Usage:
  check_post3d.py map     FIXTURE_DIR OUTDIR   map: |p|, p_n, regime, u*, tau_c, slip per cell;
                                               arrows; contact edge; fitted and Hertz ellipses
  check_post3d.py creep   FIXTURE_DIR OUTDIR   creep3d: Fx, Fy, Mz per point == the sweep files
  check_post3d.py history FIXTURE_DIR OUTDIR   history of a 3D file: Fy/Fn, Mz, eta, phi
  check_post3d.py export  FIXTURE_DIR OUTDIR   export of (time, y, x) fields: long format
  check_post3d.py profile FIXTURE_DIR OUTDIR   traction of a 3D file: the row nearest --y
  check_post3d.py realsweep SWEEP.nc OUTDIR    creep3d of a rollsim 3D sweep: every drawn point
                                               == Fx, Fy, Mz of the file at that point
  check_post3d.py legend  SWEEP.nc OUTDIR      creep3d of a sweep over xi x spin: the series
                                               labels give phi with its units (1/mm)
  check_post3d.py real    RUN.nc OUTDIR [ROLLSIM CASE [--set ...]]
                                               map of a rollsim 3D run: |p| and p_n per cell,
                                               arrow count == cells with p_n > 0, the fitted
                                               ellipse against the discrete patch and against
                                               Hertz's a, b, p0 from `rollsim check CASE`; the
                                               regime map's counts == n_exterior... of the file;
                                               u*, tau_c maps == the file when stored

Each check prints what it compares and exits 1 on the first failure.
"""
import csv
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
POSTPROC = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import make_fixtures3d as fx  # noqa: E402

CLI = [sys.executable, os.path.join(POSTPROC, "rollsim_post.py")]


def fail(msg):
    print(f"FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print(f"ok: {msg}")


def plotted(args, out_png, out_csv):
    """Run a figure command with --data; the figure must be written; rows of the CSV as dicts."""
    for f in (out_png, out_csv):
        if os.path.exists(f):
            os.remove(f)
    proc = subprocess.run(CLI + args + ["-o", out_png, "--data", out_csv], capture_output=True,
                          text=True)
    if proc.returncode != 0:
        fail(f"{' '.join(args)}: exit {proc.returncode}: {proc.stderr.strip()}")
    check(os.path.getsize(out_png) > 20000, f"{os.path.basename(out_png)} written "
          f"({os.path.getsize(out_png)} bytes)")
    with open(out_csv, newline="") as f:
        return list(csv.DictReader(f))


def rows_of(rows, quantity, panel=None):
    return [r for r in rows if r["quantity"] == quantity and (panel is None or
                                                                int(r["panel"]) == panel)]


def cell_values(rows, x, y):
    """The drawn values of map rows as an (ny, nx) array on the file's grid (NaN where absent)."""
    out = np.full((len(y), len(x)), np.nan)
    for r in rows:
        i = int(np.argmin(np.abs(x - float(r["x"]))))
        j = int(np.argmin(np.abs(y - float(r["y"]))))
        check_quiet(abs(x[i] - float(r["x"])) < 1e-12 and abs(y[j] - float(r["y"])) < 1e-12,
                    f"row at ({r['x']}, {r['y']}) is a cell centre")
        out[j, i] = float(r["value"])
    return out


def check_quiet(cond, msg):
    if not cond:
        fail(msg)


def read_nc(path, name, index=None):
    with netCDF4.Dataset(path) as ds:
        v = ds.variables[name]
        data = v[...] if index is None else v[index]
        return np.ma.filled(np.ma.asarray(data, dtype=np.float64), np.nan)


# ---- map on the synthetic file --------------------------------------------------------------

def check_map(fixdir, out):
    os.makedirs(out, exist_ok=True)
    run = os.path.join(fixdir, "run3d.nc")
    x, y = fx.grid()
    X, Y = np.meshgrid(x, y)
    pn = fx.pressure()
    contact = pn > 0.0
    n_contact = int(contact.sum())

    # Pressure map: the Hertz pressure exactly, its maximum P0 at the centre cell.
    rows = plotted(["map", run, "--field", "pressure"], f"{out}/p.png", f"{out}/p.csv")
    drawn = cell_values(rows_of(rows, "pressure"), x, y)
    check(np.array_equal(drawn, pn), f"p_n drawn == P0 sqrt(1 - x²/a² - y²/b²) in all "
          f"{pn.size} cells")
    check(np.nanmax(drawn) == fx.P0, f"max p_n drawn {np.nanmax(drawn)!r} == p0 = {fx.P0}")

    # Traction map at the last record: |p| = hypot(px, py) per cell; one arrow per cell in
    # contact (--arrows 40 >= 31 cells: no thinning) holding (px, py).
    k = len(fx.TIMES) - 1
    f = fx.fields(k)
    rows = plotted(["map", run, "--arrows", "40"], f"{out}/t.png", f"{out}/t.csv")
    drawn = cell_values(rows_of(rows, "traction"), x, y)
    expect = np.hypot(f["px"], f["py"])
    err = float(np.max(np.abs(drawn - expect)))
    check(err <= 1e-12 * fx.P0, f"|p| drawn == hypot(px, py) of record {k} (max error {err:.2e})")
    centre = fx.MU * fx.P0 * math.hypot(fx.C[k], fx.D[k])
    got = drawn[fx.NY // 2, fx.NX // 2]
    check(abs(got - centre) <= 1e-12 * centre,
          f"|p| drawn at the centre {got:.10g} == mu p0 sqrt(C² + D²) = {centre:.10g}")
    ax_, ay_ = rows_of(rows, "arrow_x"), rows_of(rows, "arrow_y")
    check(len(ax_) == n_contact and len(ay_) == n_contact,
          f"arrows drawn {len(ax_)} == cells in contact {n_contact}")
    ux, uy = cell_values(ax_, x, y), cell_values(ay_, x, y)
    check(np.array_equal(np.isfinite(ux), contact), "arrows exactly on the cells with p_n > 0")
    check(np.array_equal(ux[contact], f["px"][contact]) and
          np.array_equal(uy[contact], f["py"][contact]), "arrow components == (px, py)")

    # The ellipse: second moments of the contact cells; within one cell of the analytic a, b.
    a, b = (float(v) for v in (rows_of(rows, "ellipse_semi_axes")[0][c] for c in ("x", "y")))
    check(abs(a - fx.A) <= fx.DX and abs(b - fx.B) <= fx.DY,
          f"fitted semi-axes a = {a:.4f} (A = {fx.A}, dx = {fx.DX:.4f}), b = {b:.4f} "
          f"(B = {fx.B}, dy = {fx.DY:.4f}): within one cell")
    xc, yc = (float(rows_of(rows, "ellipse_centre")[0][c]) for c in ("x", "y"))
    check(abs(xc) < 1e-12 and abs(yc) < 1e-12, f"fitted centre ({xc:.1e}, {yc:.1e}) == (0, 0)")
    # The contact edge: cell sides between contact and exterior. Its vertical sides, counted
    # per row, are 2 per row with contact (the patch is convex); its points are cell corners.
    edge = rows_of(rows, "contact_edge")
    ex = np.array([float(r["x"]) for r in edge])
    ey = np.array([float(r["y"]) for r in edge])
    nseg = len(edge) // 2
    vertical = sum(1 for s in range(nseg) if ex[2 * s] == ex[2 * s + 1])
    rows_in_contact = int(contact.any(axis=1).sum())
    check(vertical == 2 * rows_in_contact,
          f"contact edge: {vertical} vertical sides == 2 x {rows_in_contact} rows in contact")
    cols_in_contact = int(contact.any(axis=0).sum())
    check(nseg - vertical == 2 * cols_in_contact,
          f"contact edge: {nseg - vertical} horizontal sides == 2 x {cols_in_contact} columns")
    def off_side(c, c0, d):   # distance from the nearest cell side, in cells
        u = (c - c0) / d - 0.5
        return float(np.max(np.abs(u - np.round(u))))
    check(max(off_side(ex, x[0], fx.DX), off_side(ey, y[0], fx.DY)) < 1e-9,
          "contact-edge points are cell corners")

    # Default thinning (25 arrows at most along each axis): every 2nd cell of 31, through the
    # centre cell.
    rows = plotted(["map", run], f"{out}/t2.png", f"{out}/t2.csv")
    lattice = np.zeros_like(contact)
    lattice[np.ix_((np.arange(fx.NY) - fx.NY // 2) % 2 == 0,
                   (np.arange(fx.NX) - fx.NX // 2) % 2 == 0)] = True
    check(len(rows_of(rows, "arrow_x")) == int((lattice & contact).sum()),
          f"default --arrows 25 on 31 x 25 cells: {int((lattice & contact).sum())} arrows "
          "(every 2nd cell in contact)")

    # Hertz semi-axes from the attributes when the file has them.
    rows = plotted(["map", os.path.join(fixdir, "run3d_hertz.nc")], f"{out}/h.png",
                   f"{out}/h.csv")
    r = rows_of(rows, "ellipse_semi_axes")[0]
    check(float(r["x"]) == fx.A and float(r["y"]) == fx.B and r["series"].startswith("Hertz"),
          f"Hertz ellipse from hertz_a, hertz_b: {r['series']}")

    # Several times: one panel per nearest record; regime, u*, tau_c, slip as stored.
    for field, name in (("regime", "regime"), ("ustar", "ustar"), ("tauc", "tauc")):
        rows = plotted(["map", run, "--field", field, "--time", "0", "1.2e-4"],
                       f"{out}/{field}.png", f"{out}/{field}.csv")
        for panel, record in ((0, 0), (1, 1)):
            drawn = cell_values(rows_of(rows, field, panel), x, y)
            check(np.array_equal(drawn, fx.fields(record)[name].astype(np.float64)),
                  f"{field} map panel {panel} (--time {(0, 1.2e-4)[panel]}) == record {record}")
    # A sweep file with fields: one panel per point (--select picks), the point's keys in the
    # point columns.
    sw = os.path.join(fixdir, "sweep3d_fields.nc")
    rows = plotted(["map", sw], f"{out}/sw.png", f"{out}/sw.csv")
    for panel, xi in enumerate(fx.XI_FIELDS):
        prow = rows_of(rows, "traction", panel)
        g = fx.sweep_fields(xi)
        check(float(prow[0]["rolling.creepage"]) == xi and
              np.array_equal(cell_values(prow, x, y), np.hypot(g["px"], g["py"])),
              f"sweep map panel {panel}: rolling.creepage = {xi}, |p| == the point's fields")
    rows = plotted(["map", sw, "--field", "regime", "--select", "rolling.creepage=-0.0011"],
                   f"{out}/sw1.png", f"{out}/sw1.csv")
    reg = rows_of(rows, "regime")
    check({r["panel"] for r in reg} == {"0"} and float(reg[0]["rolling.creepage"]) == -0.001 and
          np.array_equal(cell_values(reg, x, y), fx.sweep_fields(-0.001)["regime"]),
          "--select rolling.creepage=-0.0011: one panel, the point -0.001, its regimes")
    rows = plotted(["map", run, "--field", "slip", "--arrows", "31"], f"{out}/s.png",
                   f"{out}/s.csv")
    drawn = cell_values(rows_of(rows, "slip"), x, y)
    check(np.array_equal(drawn, np.hypot(f["slip_x"], f["slip_y"])), "slip map == |s| of the file")


# ---- creep3d --------------------------------------------------------------------------------

def check_creep(fixdir, out):
    os.makedirs(out, exist_ok=True)
    rows = plotted(["creep3d", os.path.join(fixdir, "sweep3d.nc")], f"{out}/c.png",
                   f"{out}/c.csv")
    keys = {"rolling.creepage": "rolling.lateral_creepage",
            "rolling.lateral_creepage": "rolling.creepage"}
    n = 0
    for r in rows:
        q = r["quantity"]
        check_quiet(q in ("Fx", "Fy", "Mz"), f"quantity {q}")
        # the abscissa is one creepage, the point column holds the other
        other = [k for k in keys if r.get(k)]
        check_quiet(len(other) == 1, f"one point column per row: {r}")
        key = keys[other[0]]
        xi, eta = (float(r["x"]), float(r[other[0]])) if key == "rolling.creepage" else \
            (float(r[other[0]]), float(r["x"]))
        i, j = fx.XI.index(xi), fx.ETA.index(eta)
        check_quiet((i, j) != fx.MISSING, "the missing point is not drawn")
        expect = dict(zip(("Fx", "Fy", "Mz"), fx.creep_forces(xi, eta)))[q]
        check_quiet(abs(float(r["y"]) - expect) <= 1e-12 * max(1.0, abs(expect)),
                    f"{q}({xi}, {eta}) drawn {r['y']} == {expect!r}")
        n += 1
    expected_rows = 3 * 2 * (len(fx.XI) * len(fx.ETA) - 1)
    check(n == expected_rows, f"creep3d sweep3d.nc: {n} points == 3 quantities x 2 creepages x "
          f"{len(fx.XI) * len(fx.ETA) - 1} stored points, each == creep_forces()")
    panels = {(r["quantity"], r["panel"]) for r in rows}
    check(len(panels) == 6, "6 panels: Fx, Fy, Mz against xi and against eta")

    rows = plotted(["creep3d", os.path.join(fixdir, "sweep3d.nc"), "--x",
                    "rolling.lateral_creepage"], f"{out}/cx.png", f"{out}/cx.csv")
    check(len(rows) == 3 * (len(fx.XI) * len(fx.ETA) - 1) and
          all(float(r["x"]) in fx.ETA and r["rolling.creepage"] for r in rows),
          f"--x rolling.lateral_creepage: {len(rows)} points, all against eta, one line per xi")
    rows = plotted(["creep3d", os.path.join(fixdir, "sweep3d_spin.nc")], f"{out}/cs.png",
                   f"{out}/cs.csv")
    for r in rows:
        phi, mu = float(r["x"]), float(r["friction.mu"])
        expect = dict(zip(("Fx", "Fy", "Mz"), fx.creep_forces(0.0, 0.0, phi, mu)))[r["quantity"]]
        check_quiet(abs(float(r["y"]) - expect) <= 1e-12 * max(1.0, abs(expect)),
                    f"spin sweep {r['quantity']}({phi}, mu {mu}) == {expect}")
    check(len(rows) == 3 * len(fx.SPIN) * len(fx.MUS),
          f"creep3d sweep3d_spin.nc: {len(rows)} points against phi, one series per mu, "
          "each == creep_forces()")


# ---- history and export ---------------------------------------------------------------------

def check_history(fixdir, out):
    os.makedirs(out, exist_ok=True)
    run = os.path.join(fixdir, "run3d.nc")
    rows = plotted(["history", run], f"{out}/h.png", f"{out}/h.csv")
    sc = [fx.scalars(k) for k in range(len(fx.TIMES))]
    for q, expect in (("Fy/Fn", [s["Fy"] / s["Fn"] for s in sc]), ("Mz", [s["Mz"] for s in sc]),
                      ("traction_coefficient", [s["traction_coefficient"] for s in sc]),
                      ("lateral_creepage", [s["lateral_creepage"] for s in sc]),
                      ("spin", [s["spin"] for s in sc]), ("n_plastic", [s["n_plastic"] for s in sc])):
        got = [float(r["y"]) for r in rows_of(rows, q)]
        check(len(got) == len(expect) and
              np.allclose(got, expect, rtol=1e-13, atol=0.0),
              f"history {q} drawn {np.round(got, 8).tolist()} == file")
    check(min(abs(s["Mz"]) for s in sc[1:]) > 1.0, "the fixture's M_z is not zero")


def check_export(fixdir, out):
    os.makedirs(out, exist_ok=True)
    run = os.path.join(fixdir, "run3d.nc")
    csv_path = f"{out}/fields.csv"
    proc = subprocess.run(CLI + ["export", run, "--var", "px", "py", "regime", "Fy", "--csv",
                                 csv_path], capture_output=True, text=True)
    if proc.returncode:
        fail(proc.stderr)
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    check(rows[0] == ["time", "y", "x", "px", "py", "regime", "Fy"],
          f"export header {rows[0]} (y and x in the fields' order although the file defines x "
          "first)")
    body = rows[1:]
    nt, ny, nx = len(fx.TIMES), fx.NY, fx.NX
    check(len(body) == nt * ny * nx, f"{len(body)} rows == {nt} records x {ny} x {nx} cells")
    x, y = fx.grid()
    for n, r in enumerate(body):
        k, rest = divmod(n, ny * nx)
        j, i = divmod(rest, nx)
        f = fx.fields(k)
        check_quiet(float(r[0]) == fx.TIMES[k] and float(r[1]) == y[j] and float(r[2]) == x[i],
                    f"row {n}: coordinates")
        check_quiet(float(r[3]) == f["px"][j, i] and float(r[4]) == f["py"][j, i] and
                    int(r[5]) == f["regime"][j, i] and float(r[6]) == fx.scalars(k)["Fy"],
                    f"row {n}: values")
    check(True, "every row: time, y, x (x fastest) and px, py, regime, Fy == the fixture")


def check_profile(fixdir, out):
    os.makedirs(out, exist_ok=True)
    run = os.path.join(fixdir, "run3d.nc")
    x, y = fx.grid()
    # rows at y = 0.384 and 0.576 mm (dy = 0.192): 0.5 is nearer the second, row 15
    rows = plotted(["traction", run, "--y", "0.5", "--time", "0", "2e-4"], f"{out}/p.png",
                   f"{out}/p.csv")
    row = int(np.argmin(np.abs(y - 0.5)))
    check(row == 15, f"row nearest y = 0.5 mm: {row} (y = {y[row]:.4f})")
    for panel, k in ((0, 0), (1, 2)):
        f = fx.fields(k)
        for q, expect in (("px", f["px"][row]), ("py", f["py"][row]), ("g", fx.MU * f["pn"][row]),
                          ("abs_p", np.hypot(f["px"][row], f["py"][row])),
                          ("tau_c", -f["tauc"][row] if f["px"].sum() < 0 else f["tauc"][row])):
            got = rows_of(rows, q, panel)
            gx = np.array([float(r["x"]) for r in got])
            gy = np.array([float(r["y"]) for r in got])
            check_quiet(np.array_equal(gx, x), f"{q}: x of the cells")
            check_quiet(all(float(r["row_y"]) == y[row] for r in got), "row_y column")
            check(np.array_equal(gy, expect), f"panel {panel} (record {k}): {q} along x at row "
                  f"{row} == the fixture")
        title = rows_of(rows, "px", panel)[0]["panel_title"]
        check(f"row {row}" in title, f"panel title names the row: {title}")
    # the default row is the centre line
    rows = plotted(["traction", run], f"{out}/c.png", f"{out}/c.csv")
    got = np.array([float(r["y"]) for r in rows_of(rows, "px")])
    check(np.array_equal(got, fx.fields(2)["px"][fx.NY // 2]), "default --y 0: the centre row")


# ---- a real rollsim 3D run ------------------------------------------------------------------

def hertz_from_check(rollsim, case, sets):
    """(a, b, p0) that `rollsim check` derives for the case (elliptic integrals, independent of
    the discrete normal problem and of this post-processing)."""
    proc = subprocess.run([rollsim, "check", case] + sets, capture_output=True, text=True)
    if proc.returncode:
        fail(f"rollsim check {case}: {proc.stderr}")
    values = {}
    for line in proc.stdout.splitlines():
        key, _, rest = line.partition(":")
        values[key.strip()] = rest.split("#")[0].strip()
    a, b = (float(v) for v in values["hertz.semi_axes"].strip("[]").split(","))
    return a, b, float(values["hertz.peak_pressure"])


def check_real(path, out, rollsim=None, case=None, *sets):
    os.makedirs(out, exist_ok=True)
    with netCDF4.Dataset(path) as ds:
        check(ds.dimensions["y"].size > 1, f"{os.path.basename(path)}: a 3D file "
              f"({ds.dimensions['x'].size} x {ds.dimensions['y'].size} cells)")
    x, y = read_nc(path, "x"), read_nc(path, "y")
    px, py, pn = (read_nc(path, v, -1) for v in ("px", "py", "pn"))
    contact = pn > 0.0
    rows = plotted(["map", path, "--arrows", str(max(len(x), len(y)))], f"{out}/real.png",
                   f"{out}/real.csv")
    drawn = cell_values(rows_of(rows, "traction"), x, y)
    check(np.array_equal(drawn, np.hypot(px, py)), "|p| drawn == hypot(px, py) of the last record")
    check(len(rows_of(rows, "arrow_x")) == int(contact.sum()),
          f"arrows {len(rows_of(rows, 'arrow_x'))} == cells with p_n > 0 ({int(contact.sum())})")
    r = rows_of(rows, "ellipse_semi_axes")[0]
    a, b = float(r["x"]), float(r["y"])
    dx, dy = float(np.diff(x).mean()), float(np.diff(y).mean())
    X, Y = np.meshgrid(x, y)
    # half extents of the discrete patch (outer cell sides)
    ha = 0.5 * (X[contact].max() - X[contact].min() + dx)
    hb = 0.5 * (Y[contact].max() - Y[contact].min() + dy)
    if r["series"].startswith("Hertz"):
        check(True, f"Hertz ellipse from the file's attributes: a = {a:.4g}, b = {b:.4g} mm")
    check(abs(a - ha) <= dx and abs(b - hb) <= dy,
          f"ellipse a = {a:.4f}, b = {b:.4f} mm vs the discrete patch's half extents "
          f"{ha:.4f}, {hb:.4f} (cells {dx:.4f} x {dy:.4f} mm): within one cell")
    if rollsim:
        ha_, hb_, p0 = hertz_from_check(rollsim, case, list(sets))
        # A rollsim 3D file carries Hertz's semi-axes (attributes hertz_a, hertz_b at the
        # load hertz_load): the map draws that ellipse, the one `rollsim check` prints (to
        # its 6 digits), not an ellipse fitted to the contact cells.
        check(r["series"].startswith("Hertz") and abs(a / ha_ - 1) <= 1e-5 and
              abs(b / hb_ - 1) <= 1e-5,
              f"{r['series']!r} ellipse a = {a:.6g}, b = {b:.6g} vs Hertz a = {ha_:.6g}, "
              f"b = {hb_:.6g} mm (rollsim check)")
    rows = plotted(["map", path, "--field", "pressure"], f"{out}/real_p.png", f"{out}/real_p.csv")
    drawn = cell_values(rows_of(rows, "pressure"), x, y)
    with netCDF4.Dataset(path) as ds:
        fn = float(ds.variables["Fn"][-1])
    load = float(np.nansum(drawn)) * dx * dy
    check(np.array_equal(drawn, pn) and abs(load - fn) <= 1e-9 * fn,
          f"p_n drawn == the file's; its sum x dx dy = {load:.6g} N == Fn = {fn:.6g} N")
    if rollsim:
        # docs/verification.md 9: the discrete pressure converges to Hertz's (1 % on 60 x 60); on
        # this coarser grid the peak cell sits half a cell off the centre (an even number of
        # cells), which costs ((dx/a)^2 + (dy/b)^2)/8, 0.3 % at a/9, b/9: 1 % holds with room.
        pmax = float(np.nanmax(drawn))
        check(abs(pmax - p0) <= 0.01 * p0,
              f"max p_n drawn {pmax:.2f} vs Hertz p0 = {p0:.2f} N/mm² (rollsim check): "
              f"{100 * abs(pmax - p0) / p0:.2f} % <= 1 %")
    # The regime map: its cell counts per code == the scalars n_exterior, ... of the record.
    rows = plotted(["map", path, "--field", "regime"], f"{out}/real_r.png", f"{out}/real_r.csv")
    drawn = cell_values(rows_of(rows, "regime"), x, y)
    check(np.array_equal(drawn, read_nc(path, "regime", -1)), "regime map == the file's codes")
    with netCDF4.Dataset(path) as ds:
        counts = [int(ds.variables[n][-1]) for n in ("n_exterior", "n_adhesion", "n_slip",
                                                      "n_plastic")]
    drawn_counts = [int((drawn == c).sum()) for c in range(4)]
    check(drawn_counts == counts, f"regime map cells per regime E/H/S/P {drawn_counts} == "
          f"n_exterior, n_adhesion, n_slip, n_plastic {counts}")
    for field in ("ustar", "tauc"):
        with netCDF4.Dataset(path) as ds:
            if field not in ds.variables:
                continue
        rows = plotted(["map", path, "--field", field], f"{out}/real_{field}.png",
                       f"{out}/real_{field}.csv")
        drawn = cell_values(rows_of(rows, field), x, y)
        check(np.array_equal(drawn, read_nc(path, field, -1)), f"{field} map == the file's")
    check(rows[0]["panel_title"] == "steady rolling (record 0)",
          "a steady file's panel is titled 'steady rolling (record 0)'")
    proc = subprocess.run(CLI + ["export", path, "--var", "px", "py", "--csv", f"{out}/e.csv"],
                          capture_output=True, text=True)
    check_quiet(proc.returncode == 0, proc.stderr)
    with open(f"{out}/e.csv", newline="") as f:
        exp = list(csv.reader(f))
    body = np.array([[float(v) for v in r] for r in exp[1:]])
    check(exp[0] == ["time", "y", "x", "px", "py"] and len(body) == px.size and
          np.array_equal(body[:, 3], px.ravel()) and np.array_equal(body[:, 4], py.ravel()) and
          np.array_equal(body[:, 1], Y.ravel()) and np.array_equal(body[:, 2], X.ravel()),
          f"export px py: {len(body)} rows time,y,x,px,py == the file (x fastest)")
    rows = plotted(["history", path], f"{out}/real_h.png", f"{out}/real_h.csv")
    with netCDF4.Dataset(path) as ds:
        fy_fn = float(ds.variables["Fy"][-1]) / float(ds.variables["Fn"][-1])
        mz = float(ds.variables["Mz"][-1])
    got = rows_of(rows, "Fy/Fn")[-1]
    check(float(got["y"]) == fy_fn and float(rows_of(rows, "Mz")[-1]["y"]) == mz,
          f"history: Fy/Fn = {fy_fn:.6g}, Mz = {mz:.6g} N mm as in the file")


def check_real_sweep(path, out):
    os.makedirs(out, exist_ok=True)
    rows = plotted(["creep3d", path], f"{out}/creep3d.png", f"{out}/creep3d.csv")
    with netCDF4.Dataset(path) as ds:
        dims = [d for d in ds.variables["Fx"].dimensions]
        keys = [ds.variables[d].key for d in dims]
        coords = [np.asarray(ds.variables[d][:]) for d in dims]
        data = {q: np.ma.filled(ds.variables[q][...].astype(np.float64), np.nan)
                for q in ("Fx", "Fy", "Mz")}
    swept = [k for k in keys if k.startswith("rolling.")]
    n = 0
    for r in rows:
        idx = []
        for k, c in zip(keys, coords):
            v = float(r[k]) if r.get(k) else float(r["x"])
            hit = np.nonzero(c == v)[0]
            check_quiet(hit.size == 1, f"{k} = {v} is a coordinate value")
            idx.append(int(hit[0]))
        check_quiet(float(r["y"]) == data[r["quantity"]][tuple(idx)],
                    f"{r['quantity']} at {tuple(idx)}: drawn {r['y']} == the file")
        n += 1
    finite = sum(int(np.isfinite(v).sum()) for v in data.values())
    check(n == finite * len(swept), f"creep3d {os.path.basename(path)}: {n} points drawn == "
          f"{finite} values of Fx, Fy, Mz x {len(swept)} creepage keys, each == the file")


def check_real_legend(path, out):
    """creep3d of a sweep whose series are told apart by a key with units (the spin, 1/mm):
    each series' label gives the key's value with the units of its coordinate variable."""
    os.makedirs(out, exist_ok=True)
    rows = plotted(["creep3d", path], f"{out}/legend.png", f"{out}/legend.csv")
    with netCDF4.Dataset(path) as ds:
        units = {ds.variables[d].key: ds.variables[d].units for d in ds.variables["Fx"].dimensions}
    labelled = [k for k in units if k in rows[0] and units[k] not in ("", "1")]
    check(labelled == ["rolling.spin"] and units["rolling.spin"] == "1/mm",
          f"series told apart by rolling.spin [{units.get('rolling.spin')}]")
    bad = [r["series"] for r in rows
           if f"φ = {float(r['rolling.spin']):.6g} 1/mm" not in r["series"]]
    check(not bad, f"every series label gives φ with its units 1/mm: "
          f"{sorted({r['series'] for r in rows})} {bad[:1]}")


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    cmd, args = argv[1], argv[2:]
    {"map": check_map, "creep": check_creep, "history": check_history, "export": check_export,
     "profile": check_profile, "real": check_real, "realsweep": check_real_sweep,
     "legend": check_real_legend}[cmd](*args)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
