"""Command line of rollsim_post: argument parsing and dispatch (see postproc/README.md)."""
import argparse
import os
import sys

from . import PostError, figure_format
from . import extract
from .runfile import RunFile

PROG = "rollsim_post"

DESCRIPTION = """\
Figures and CSV from rollsim netCDF output (interfaces.md, "Output file").
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

def cmd_traction(args):
    figure_format(args.output)
    with RunFile(args.file) as run:
        indices = extract.record_indices(run, args.time)
        profiles = [extract.traction_profile(run, i, mu=args.mu) for i in indices]
        _warn_status(run)
        _plots().plot_traction(profiles, _title(args, run), args.output)


def cmd_regimes(args):
    figure_format(args.output)
    with RunFile(args.file) as run:
        fmap, flags = extract.regime_map(run)
        _warn_status(run)
        _plots().plot_regimes(fmap, flags, _title(args, run), args.output)


def cmd_history(args):
    figure_format(args.output)
    with RunFile(args.file) as run:
        data, units = extract.history(run)
        mu = args.mu if args.mu is not None else run.mu()
        _warn_status(run)
        _plots().plot_history(data, units, mu, _title(args, run), args.output)


def cmd_creepcurve(args):
    figure_format(args.output)
    series = extract.creep_series(args.files, labels=args.label, group_by=args.group_by)
    _plots().plot_creepcurve(series, args.output, absolute=args.abs, title=args.title)


def cmd_plastic(args):
    figure_format(args.output)
    with RunFile(args.file) as run:
        missing = [v for v in ("ustar", "tauc") if not run.has(v)]
        if missing:
            raise PostError(f"{args.file}: no variable {' or '.join(repr(m) for m in missing)}: "
                            "the plastic figure needs ustar and tauc (run with a plasticity: "
                            "block and output.fields including ustar, tauc)")
        ustar = extract.field_map(run, "ustar")
        tauc = extract.field_map(run, "tauc")
        _warn_status(run)
        _plots().plot_plastic(ustar, tauc, _title(args, run), args.output)


def cmd_rig(args):
    figure_format(args.output)
    with RunFile(args.file) as run:
        rig = extract.rig_results(run)
        _warn_status(run)
        _plots().plot_rig(rig, _title(args, run), args.output)


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
        return s

    s = figure("traction", "p_x, +-mu p_n and tau_c along x at chosen times",
               "p_x, the traction bound g = mu p_n (and -g) and, if stored, the yield limit "
               "tau_c along x,\nwith the regimes shaded; one panel per requested time "
               "(nearest stored record).\nmu comes from friction.mu in the file's case "
               "attribute (default 0.5).")
    s.add_argument("file", metavar="FILE")
    s.add_argument("--time", type=float, nargs="+", metavar="T",
                   help="times in s; each picks the nearest stored record (default: the last)")
    s.add_argument("--mu", type=float, help="override the coefficient of friction")
    s.set_defaults(func=cmd_traction)

    s = figure("regimes", "x-t map of the regime (E/H/S/P)",
               "x-t map of the contact regime: exterior, adhesion (H), slip, plastic.")
    s.add_argument("file", metavar="FILE")
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
    s.set_defaults(func=cmd_creepcurve)

    s = figure("plastic", "u* and tau_c over x and t",
               "Accumulated plastic deformation u* and yield limit tau_c over x and t.\n"
               "Needs ustar and tauc in the file (output.fields).")
    s.add_argument("file", metavar="FILE")
    s.set_defaults(func=cmd_plastic)

    s = figure("rig", "twin-disc traction coefficient per protocol step and per revolution",
               "Twin-disc run (twin_disc: block): traction coefficient of each protocol step "
               "(mean over its\naveraging window) against the slip, and per revolution with "
               "the slip.")
    s.add_argument("file", metavar="FILE")
    s.set_defaults(func=cmd_rig)

    s = sub.add_parser("export", help="variables to CSV", epilog=EXPORT_EPILOG,
                       description="Write variables of a rollsim file to CSV.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    s.add_argument("file", metavar="FILE")
    s.add_argument("--var", nargs="+", action="extend", required=True, metavar="NAME",
                   help="variables to export (repeatable)")
    s.add_argument("--csv", required=True, metavar="OUT", help="CSV file to write, - for stdout")
    s.set_defaults(func=cmd_export)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
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
