"""Command line of rollsim_post: argument parsing and dispatch (see postproc/README.md)."""
import argparse
import os
import sys

import numpy as np

from . import PostError, figure_format
from . import extract
from . import field3d
from . import sweep
from .record import Recorder
from .runfile import RunFile, case_value

PROG = "rollsim_post"

DESCRIPTION = """\
Figures and CSV from rollsim netCDF output (docs/file-format.md).
Figures are drawn headless; the format follows the extension of -o (.png, .svg, .pdf).
Errors (missing file, not netCDF, missing variable, no records) print one line on
stderr naming the file/variable and exit with status 2."""

EXPORT_EPILOG = """\
CSV layout: a header line with the column names, then one row per combination of
the dimensions the requested variables use, in the file's dimension order (time
before x; the last varies fastest). The first columns are those dimensions'
coordinates (coordinate variable, or the index if there is none), then one column
per variable in the order given. Hence:
  time-only variables      time,Fx,Fn            one row per record
  (time, x) variables      time,x,px             long format, one row per record and cell
  3D (time, y, x) fields   time,y,x,px,py        one row per record and cell (x fastest)
  mixed                    time,x,px,Fx          time-only values repeated on every x row
  sweep-file results       plasticity_k_rel,rolling_creepage,traction_coefficient
Numbers are written with Python's repr(), which reads back to the identical double;
missing (fill) values are empty cells. Use --csv - for stdout."""


def _warn_status(run):
    """Called once the data are read: a partial file is usable, but say so."""
    status = run.status
    if status and status != "complete":
        print(f"{PROG}: warning: {run.path}: status is '{status}'; results may be partial",
              file=sys.stderr)


def _title(args, run):
    return args.title if args.title else (run.title or os.path.basename(run.path))


def _plots():
    """matplotlib is imported only once the data are read, so input errors stay one clean line."""
    from . import plots
    return plots


# ---- subcommands ---------------------------------------------------------------------------

def _selection(args):
    """--select KEY=VALUE... as a dict (PostError for a malformed one)."""
    out = {}
    for item in args.select or []:
        key, eq, value = item.partition("=")
        try:
            out[key] = float(value)
        except ValueError:
            raise PostError(f"--select {item}: expected KEY=NUMBER, e.g. plasticity.k_rel=0.6") from None
        if not eq or not key:
            raise PostError(f"--select {item}: expected KEY=NUMBER")
    return out


def _finish(args, rec):
    if getattr(args, "data", None):
        rec.write(args.data)


def _sweep_only(args, run, option):
    if getattr(args, option.replace("-", "_"), None) and not run.is_sweep():
        raise PostError(f"{run.path}: --{option} applies to sweep files (rollsim sweep)")


def _panels(run, args):
    """Points of a sweep file grouped into panels (--overlay, --select)."""
    pts = sweep.points(run, _selection(args))
    groups = sweep.group(pts, run, args.overlay)
    panels = []
    for g in groups:
        rest = [k for k in g[0].values if k != args.overlay]
        title = g[0].label(run, rest) if args.overlay else g[0].label(run)
        panels.append((title, g))
    return panels


def _series_label(run, point, key):
    """Label of a point inside an --overlay panel: 'elastic' when the yield limit is never
    reached (tau_c0 >= mu max p_n), else the overlay key's value."""
    return sweep.describe(key, point.values[key], sweep.sweep_units(run, key))


def cmd_traction(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        if run.is_sweep():
            run.require_2d("traction", "map FILE --field traction (|p| and arrows over x and y)")
        elif args.y is not None and not run.is_3d():
            raise PostError(f"{run.path}: --y applies to 3D files")
        for opt in ("overlay", "select"):
            _sweep_only(args, run, opt)
        if run.is_3d() and not run.is_sweep():
            indices = extract.record_indices(run, args.time)
            profiles = [field3d.row_profile(run, i, args.y or 0.0, mu=args.mu) for i in indices]
            _warn_status(run)
            _plots().plot_traction(profiles, _title(args, run), args.output, rec)
        elif run.is_sweep():
            if args.time:
                raise PostError(f"{run.path}: --time applies to time-history files, not sweeps")
            sweep.require_profiles(run)
            panels = []
            for title, group in _panels(run, args):
                profs = [sweep.sweep_profile(run, p, mu=args.mu) for p in group]
                labels = ["elastic" if pr.elastic else
                          (_series_label(run, p, args.overlay) if args.overlay else "")
                          for p, pr in zip(group, profs)]
                if not args.overlay and profs[0].elastic:
                    title = f"{title} (elastic: τ_c never reached)"
                panels.append((title, list(zip(labels, profs))))
            _warn_status(run)
            _plots().plot_sweep_traction(panels, _title(args, run), args.output, rec)
        else:
            indices = extract.record_indices(run, args.time)
            profiles = [extract.traction_profile(run, i, mu=args.mu) for i in indices]
            _warn_status(run)
            _plots().plot_traction(profiles, _title(args, run), args.output, rec)
    _finish(args, rec)


def cmd_friction(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        if run.is_sweep():
            raise PostError(f"{run.path}: friction needs the file of rollsim run (field mu)")
        index = extract.record_indices(run, [args.time] if args.time is not None else None)[0]
        prof = extract.friction_profile(run, index)
        _warn_status(run)
        _plots().plot_friction(prof, _title(args, run), args.output, rec)
    _finish(args, rec)


def cmd_regimes(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        run.require_2d("regimes", "map FILE --field regime (the regime over x and y)")
        for opt in ("overlay", "select"):
            _sweep_only(args, run, opt)
        if run.is_sweep():
            sweep.require_profiles(run, ("regime",))
            rows_key = args.overlay or run.sweep_key(sweep.sweep_dims(run)[-1])
            args.overlay = rows_key
            panels = []
            for title, group in _panels(run, args):
                rows = []
                for p in group:
                    pr = sweep.sweep_profile(run, p) if run.has("px") else None
                    reg = sweep.field_at(run, "regime", p)
                    prof = sweep.SweepProfile(p, 0.0, run.values("x"), None, None, None,
                                              regime=np.where(np.isnan(reg), -1, reg).astype(int))
                    rows.append((_series_label(run, p, rows_key) +
                                 (" (elastic)" if pr is not None and pr.elastic else ""), prof))
                panels.append((title, rows))
            _warn_status(run)
            name, unit, _ = sweep.KEY_NAMES.get(rows_key, (rows_key, "", 1))
            _plots().plot_sweep_regimes(panels, run.regime_flags(), name, _title(args, run),
                                        args.output, rec)
        else:
            fmap, flags = extract.regime_map(run)
            _warn_status(run)
            _plots().plot_regimes(fmap, flags, _title(args, run), args.output, rec)
    _finish(args, rec)


def cmd_history(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        if run.is_sweep():
            raise PostError(f"{run.path}: a sweep file has no time histories: use creepcurve "
                            "(or creep3d for a 3D sweep)")
        data, units = extract.history(run)
        extra, extra_units = field3d.history_extra(run) if run.is_3d() else (None, None)
        mu = args.mu if args.mu is not None else run.mu()
        _warn_status(run)
        _plots().plot_history(data, units, mu, _title(args, run), args.output, rec,
                              extra=extra, extra_units=extra_units)
    _finish(args, rec)


MAX_MAP_PANELS = 12


def cmd_map(args):
    figure_format(args.output)
    rec = Recorder()
    if args.field not in field3d.MAP_FIELDS:
        raise PostError(f"--field {args.field}: expected one of {', '.join(field3d.MAP_FIELDS)}")
    with RunFile(args.file) as run:
        run.require_3d("map")
        _sweep_only(args, run, "select")
        if run.is_sweep():
            if args.time:
                raise PostError(f"{run.path}: --time applies to time-history files, not sweeps")
            colour = field3d.MAP_FIELDS[args.field][0]
            if not all(run.has(v) for v in colour):
                raise PostError(f"{run.path}: sweep file without the fields {', '.join(colour)}: "
                                "run the sweep with output.fields listing them")
            pts = sweep.points(run, _selection(args))
            if len(pts) > MAX_MAP_PANELS:
                raise PostError(f"{run.path}: {len(pts)} sweep points; choose at most "
                                f"{MAX_MAP_PANELS} with --select KEY=VALUE")
            maps = [field3d.field_map(run, args.field, p) for p in pts]
            for m, p in zip(maps, pts):
                m.label = p.label(run)
        else:
            indices = extract.record_indices(run, args.time)
            maps = [field3d.field_map(run, args.field, i) for i in indices]
            if case_value(run.case(), "simulation.mode") == "steady":
                for m in maps:
                    m.label = f"steady rolling (record {m.index})"
        _warn_status(run)
        from . import plots3d
        plots3d.plot_map(maps, _title(args, run), args.output, rec, max_arrows=args.arrows)
    _finish(args, rec)


def cmd_creep3d(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        panels = field3d.creep3d_panels(run, x_keys=args.x)
        _warn_status(run)
        from . import plots3d
        plots3d.plot_creep3d(panels, args.title if args.title is not None else run.title,
                             args.output, rec)
    _finish(args, rec)


def cmd_creepcurve(args):
    figure_format(args.output)
    rec = Recorder()
    series = extract.creep_series(args.files, labels=args.label, group_by=args.group_by)
    mu = None
    if args.panel:
        panels, mu = _creep_panels(args, series)
    else:
        panels = [("", series)]
    _plots().plot_creepcurve(panels, args.output, absolute=args.abs, title=args.title,
                             percent=args.percent, mu=mu, rec=rec)
    _finish(args, rec)


def _creep_panels(args, series):
    """--panel KEY: one panel per value of the swept KEY (sweep files only). When the case has
    plasticity, series whose yield limit is never reached are the elastic curve: labelled
    'elastic', drawn in every panel, and their KEY values get no panel of their own."""
    key = args.panel
    with RunFile(args.files[0]) as run:
        if len(args.files) != 1 or not run.is_sweep():
            raise PostError("--panel needs one sweep file (rollsim sweep)")
        sweep.key_dim(run, key)
        units = sweep.sweep_units(run, key)
        mus = {sweep.value_at(run, sweep.Point((), dict(s.values)), "friction.mu") for s in series}
    mark = any(s.elastic for s in series) and not all(s.elastic for s in series)
    elastic = [s for s in series if s.elastic] if mark else []
    by_value = {}
    for s in series:
        if key not in s.values:
            continue
        if not (mark and s.elastic):
            by_value.setdefault(s.values[key], []).append(s)
    if elastic:
        e = elastic[0]
        e.label = "elastic"
    panels = []
    for value, group in by_value.items():
        for s in group:
            s.label = ", ".join(sweep.describe(k, v, "") for k, v in s.values.items() if k != key) \
                or s.label
        panels.append((sweep.describe(key, value, units), group + elastic[:1]))
    if not panels:
        raise PostError(f"{args.files[0]}: no plastic series to put in panels over {key}")
    return panels, (mus.pop() if len(mus) == 1 else None)


def cmd_plastic(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        run.require_2d("plastic", "map FILE --field ustar or --field tauc")
        for opt in ("overlay", "select"):
            _sweep_only(args, run, opt)
        if run.is_sweep():
            sweep.require_profiles(run, ("ustar", "tauc"))
            panels = []
            for title, group in _panels(run, args):
                lines = []
                for p in group:
                    prof = sweep.sweep_profile(run, p)
                    label = "elastic" if prof.elastic else (
                        _series_label(run, p, args.overlay) if args.overlay else title)
                    lines.append((label, prof.x, sweep.field_at(run, "ustar", p), prof.tauc,
                                  p.values))
                panels.append((title if args.overlay else "", lines) if args.overlay
                              else (title, lines))
            _warn_status(run)
            _plots().plot_sweep_plastic(panels, _title(args, run), args.output, rec)
            _finish(args, rec)
            return
        missing = [v for v in ("ustar", "tauc") if not run.has(v)]
        if missing:
            raise PostError(f"{args.file}: no variable {' or '.join(repr(m) for m in missing)}: "
                            "the plastic figure needs ustar and tauc (run with a plasticity: "
                            "block and output.fields including ustar, tauc)")
        ustar = extract.field_map(run, "ustar")
        tauc = extract.field_map(run, "tauc")
        _warn_status(run)
        _plots().plot_plastic(ustar, tauc, _title(args, run), args.output, rec)
    _finish(args, rec)


def cmd_rig(args):
    figure_format(args.output)
    rec = Recorder()
    with RunFile(args.file) as run:
        rig = extract.rig_results(run)
        _warn_status(run)
        _plots().plot_rig(rig, _title(args, run), args.output, rec)
    _finish(args, rec)


def cmd_fit(args):
    figure_format(args.output)
    from . import fitplot
    fit = fitplot.read_fit(args.file)
    if fit["status"] and fit["status"] != "complete":
        print(f"{PROG}: warning: {args.file}: status is '{fit['status']}'; the best point so far",
              file=sys.stderr)
    rec = Recorder()
    fitplot.plot_fit(fit, args.title or fit["title"] or os.path.basename(args.file), args.output,
                     rec)
    _finish(args, rec)


def cmd_profiles(args):
    figure_format(args.output)
    from . import profiles
    prof = profiles.read_case(args.case)
    if args.rollsim:
        prof["contact"] = profiles.contact(args.case, args.rollsim)
        if prof["contact"] is None:
            print(f"{PROG}: note: {args.case} gives no profiles.vertical_load: no contact "
                  "patches to draw", file=sys.stderr)
    rec = Recorder()
    _plots().plot_profiles(prof, args.title or prof["title"] or os.path.basename(args.case),
                           args.output, rec)
    _finish(args, rec)


def cmd_wheelrail(args):
    figure_format(args.output)
    from . import profiles
    d = profiles.read_sweep(args.file)
    if d["status"] and d["status"] != "complete":
        print(f"{PROG}: warning: {args.file}: status {d['status']!r}: positions that failed are "
              "not drawn", file=sys.stderr)
    rec = Recorder()
    _plots().plot_wheelrail(d, args.title or d["title"] or os.path.basename(args.file),
                            args.output, rec)
    _finish(args, rec)


def cmd_export(args):
    with RunFile(args.file) as run:
        header, columns = extract.export_table(run, args.var)
        _warn_status(run)
        try:
            extract.write_csv(args.csv, header, columns)
        except BrokenPipeError:
            raise  # stdout closed early (e.g. | head): not an error, see main()
        except OSError as e:
            raise PostError(f"{args.csv}: cannot write: {e.strerror or e}") from None


# ---- parser --------------------------------------------------------------------------------

def build_parser():
    p = argparse.ArgumentParser(prog=PROG, description=DESCRIPTION,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    def figure(name, help_, description, title_help="figure title (default: the file's title)"):
        s = sub.add_parser(name, help=help_, description=description,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        s.add_argument("-o", "--output", required=True, metavar="OUT",
                       help="figure file; format from the extension: .png, .svg, .pdf")
        s.add_argument("--title", help=title_help)
        s.add_argument("--data", metavar="CSV",
                       help="also write the plotted series to CSV: panel, panel_title, series, "
                            "quantity, the swept keys of the point shown, x, y")
        return s

    def sweep_options(s):
        s.add_argument("--overlay", metavar="KEY",
                       help="sweep file: draw the points along the swept KEY in one panel "
                            "(default: one panel per point)")
        s.add_argument("--select", metavar="KEY=VALUE", action="append",
                       help="sweep file: only the points whose KEY is nearest VALUE (repeatable)")

    s = figure("traction", "p_x, +-mu p_n and tau_c along x at chosen times",
               "p_x, the traction bound g = mu p_n (and -g) and, if stored, the yield limit "
               "tau_c along x,\nwith the regimes shaded; one panel per requested time "
               "(nearest stored record).\nmu comes from friction.mu in the file's case "
               "attribute (default 0.5).")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--time", type=float, nargs="+", metavar="T",
                   help="times in s; each picks the nearest stored record (default: the last)")
    s.add_argument("--mu", type=float, help="override the coefficient of friction")
    s.add_argument("--y", type=float, metavar="Y",
                   help="3D file: the row of cells nearest to Y mm (default 0, the centre line); "
                        "p_y and |p| are drawn too")
    sweep_options(s)
    s.set_defaults(func=cmd_traction)

    s = figure("friction", "velocity-dependent friction: mu along x and mu against |v_s|",
               "mu of every contact cell along x (3D: a map over x and y), and against the "
               "cell's\nslip speed |v_s| over the law's curve (from the file's case attribute); needs the field mu "
               "(friction.law not coulomb).")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--time", type=float, metavar="T",
                   help="time in s; picks the nearest stored record (default: the last)")
    s.set_defaults(func=cmd_friction)

    s = figure("regimes", "x-t map of the regime (E/H/S/P)",
               "x-t map of the contact regime: exterior, adhesion (H), slip, plastic.")
    s.add_argument("file", metavar="FILE")
    sweep_options(s)
    s.set_defaults(func=cmd_regimes)

    s = figure("history", "F_x/F_n, creepage, velocity, regime counts, powers against time",
               "Time histories: F_x/F_n (with +-mu), creepage, velocity, cell counts per "
               "regime,\nfrictional and plastic power.")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--mu", type=float, help="override the coefficient of friction")
    s.set_defaults(func=cmd_history)

    s = figure("creepcurve", "traction coefficient against creepage, one line per series",
               "Traction coefficient F_x/F_n against creepage.\n"
               "A single-run file gives one point: the last record's traction_coefficient and "
               "creepage.\nFiles with the same label form one series; the label is --label, "
               "else 'KEY = value'\nof --group-by KEY read from the case attribute, else the "
               "file's title. A sweep file\n(rollsim sweep) gives one series per combination "
               "of its swept keys other than\nrolling.creepage (--label then prefixes them). "
               "Points are sorted by creepage.", title_help="figure title (default: none)")
    s.add_argument("files", nargs="+", metavar="FILE")
    s.add_argument("--label", action="append",
                   help="series label; give once (all files) or once per FILE, in order")
    s.add_argument("--group-by", metavar="KEY",
                   help="group single-run files by this dotted case key, e.g. plasticity.k_tau")
    s.add_argument("--abs", action="store_true",
                   help="plot |creepage| and |F_x/F_n| (the paper's Figure 9 quadrant)")
    s.add_argument("--percent", action="store_true", help="creepage in %% (100 xi)")
    s.add_argument("--panel", metavar="KEY",
                   help="one sweep file: one panel per value of the swept KEY (e.g. "
                        "plasticity.tau_c0); with plasticity, points whose yield limit is never "
                        "reached are drawn as 'elastic' in every panel")
    s.set_defaults(func=cmd_creepcurve)

    s = figure("plastic", "u* and tau_c over x and t",
               "Accumulated plastic deformation u* and yield limit tau_c over x and t.\n"
               "Needs ustar and tauc in the file (output.fields).")
    s.add_argument("file", metavar="FILE")
    sweep_options(s)
    s.set_defaults(func=cmd_plastic)

    s = figure("rig", "twin-disc traction coefficient per protocol step and per revolution",
               "Twin-disc run (twin_disc: block): traction coefficient of each protocol step "
               "(mean over its\naveraging window) against the slip, and per revolution with "
               "the slip.")
    s.add_argument("file", metavar="FILE")
    s.set_defaults(func=cmd_rig)

    s = figure("map", "3D file: a field over the contact patch (x, y) at chosen times",
               "3D run file (contact.dimension: 3): one field over the cells, equal aspect, with "
               "a colour bar,\nthe discrete contact edge (p_n > 0) and the contact ellipse "
               "(Hertz semi-axes from the file's\nattributes hertz_a, hertz_b, else the ellipse "
               "with the contact cells' second moments).\nVector fields (traction, slip, upl) "
               "get arrows on the cells in contact. One panel per\nrequested time (nearest "
               "stored record). --data adds a column value: one row per cell\n(quantity = "
               "the field), per arrow (arrow_x, arrow_y), the edge, the ellipse and its\n"
               "semi-axes (x = a, y = b).")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--field", default="traction", metavar="FIELD",
                   help="what to colour: traction (|p| with arrows, default), slip (|s| with "
                        "arrows), pressure, regime, ustar, tauc, upl, T1, T2 (surface "
                        "temperatures, temperature: block)")
    s.add_argument("--time", type=float, nargs="+", metavar="T",
                   help="times in s; each picks the nearest stored record (default: the last)")
    s.add_argument("--arrows", type=int, default=25, metavar="N",
                   help="at most N arrows along x and along y (every k-th cell; default 25)")
    s.add_argument("--select", metavar="KEY=VALUE", action="append",
                   help="3D sweep file with fields: only the points whose KEY is nearest VALUE "
                        "(repeatable); one panel per point")
    s.set_defaults(func=cmd_map)

    s = figure("creep3d", "3D sweep: F_x, F_y, M_z against each swept creepage",
               "3D sweep file: F_x, F_y and M_z (rows) against each swept creepage key "
               "(columns:\nrolling.creepage, rolling.lateral_creepage, rolling.spin; by default "
               "those swept over\n3 or more values); one line per combination of the other "
               "swept keys.", title_help="figure title (default: the file's title)")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--x", action="append", metavar="KEY",
                   help="abscissa: this swept creepage key (repeatable; default: every one "
                        "swept over at least 3 values)")
    s.set_defaults(func=cmd_creep3d)
    s = figure("fit", "rollsim fit: measured and simulated against the input, residuals below",
               "A fit file (rollsim fit): the measured points and the simulated values at the "
               "fitted\nparameters against the data's (last) input column, the residuals below; "
               "the fitted\nvalues with their standard errors in the legend.")
    s.add_argument("file", metavar="FILE")
    s.set_defaults(func=cmd_fit)

    s = figure("profiles", "a case's rail and wheel profiles (profiles: block)",
               "The rail and wheel profiles of a case file's profiles: block, read as rollsim "
               "reads them\n(mirror, scale, smoothing): the rail inclined by rail_inclination, "
               "the wheel lowered\nonto it (where both are functions of y) with the first point "
               "of contact marked, the\ngauge height drawn. y toward the track centre, z "
               "downward, mm. `rollsim check CASE`\nvalidates the files. With --rollsim and "
               "profiles.vertical_load: the wheel placed as\nrollsim places it (track gauge, "
               "flange back, lateral displacement) and each contact\npatch rollsim check finds "
               "marked with its contact angle, normal force and peak\npressure, its normal drawn.",
               title_help="figure title (default: the case's title)")
    s.add_argument("case", metavar="CASE.yaml")
    s.add_argument("--rollsim", metavar="BIN",
                   help="the rollsim program whose `check` gives the contact patches")
    s.set_defaults(func=cmd_profiles)

    s = figure("wheelrail", "a sweep on profiles against the lateral displacement",
               "A sweep file on profiles (rollsim sweep on a case with profiles:): per patch the "
               "contact\npoint on the rail, the contact angle, F_n, F_x and F_s on the wheel, "
               "and the lateral and\nvertical force on the wheel in track coordinates, against "
               "the wheelset's lateral\ndisplacement; a moving wheelset's file (rollsim run) "
               "against time, with the\nlateral displacement drawn beside the contact point.")
    s.add_argument("file", metavar="FILE")
    s.set_defaults(func=cmd_wheelrail)

    s = sub.add_parser("export", help="variables to CSV", epilog=EXPORT_EPILOG,
                       description="Write variables of a rollsim file to CSV.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("file", metavar="FILE")
    s.add_argument("--var", nargs="+", action="extend", required=True, metavar="NAME",
                   help="variables to export (repeatable)")
    s.add_argument("--csv", required=True, metavar="OUT", help="CSV file to write, - for stdout")
    s.set_defaults(func=cmd_export)
    return p


def _check_data_path(args):
    """--data CSV: its directory must exist, checked before anything is drawn or written."""
    path = getattr(args, "data", None)
    if path:
        folder = os.path.dirname(path) or "."
        if not os.path.isdir(folder) or not os.access(folder, os.W_OK):
            raise PostError(f"{path}: cannot write (no writable directory {folder})")


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        _check_data_path(args)
        args.func(args)
    except PostError as e:
        print(f"{PROG}: {e}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        # The reader of stdout went away (| head); silence the flush at interpreter exit.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    return 0
