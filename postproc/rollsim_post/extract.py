"""The numbers behind every figure and export, separate from plotting so tests can check them.

Nothing here draws; each function takes an open RunFile (runfile.py) or file paths and returns
arrays.
"""
import csv
import itertools
import os
import sys
from dataclasses import dataclass, field

import numpy as np

from . import PostError
from . import sweep
from .runfile import RunFile, case_value

# ---- records and grids ---------------------------------------------------------------------


def nearest_record(times, t):
    """Index of the stored record whose time is nearest to t. On an exact tie (t midway between
    two records) the earlier record wins; t outside the stored range gives the first/last record."""
    times = np.asarray(times, dtype=np.float64)
    if times.size == 0:
        raise ValueError("no records")
    return int(np.argmin(np.abs(times - float(t))))


def record_indices(run, requested_times=None):
    """Record indices for the requested times (nearest stored record each); default: the last."""
    run.require_records()
    times = run.values("time")
    if not requested_times:
        return [len(times) - 1]
    return [nearest_record(times, t) for t in requested_times]


def cell_edges(centres):
    """Edges of the cells (or records) around the given centres: midpoints inside, half a spacing
    beyond the first and last centre. A single centre gets edges +-0.5 (in its own units) unless
    a positive value makes a relative width more sensible (+-5 %)."""
    c = np.asarray(centres, dtype=np.float64)
    if c.size == 1:
        half = 0.05 * abs(c[0]) if c[0] != 0.0 else 0.5
        return np.array([c[0] - half, c[0] + half])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate(([c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]))


def regime_runs(regime_row):
    """Contiguous runs of equal regime along x: list of (first cell, last cell + 1, value)."""
    r = np.asarray(regime_row)
    runs = []
    start = 0
    for i in range(1, r.size + 1):
        if i == r.size or r[i] != r[start]:
            runs.append((start, i, int(r[start])))
            start = i
    return runs


# ---- traction (Figure 7 style) -------------------------------------------------------------


@dataclass
class TractionProfile:
    """p_x, the traction bound g = mu p_n and (if stored) tau_c along x at one record."""
    index: int
    time: float
    mu: float
    x: np.ndarray
    px: np.ndarray
    pn: np.ndarray
    g: np.ndarray
    tauc: np.ndarray = None
    regime: np.ndarray = None
    regime_flags: tuple = None
    py: np.ndarray = None    # 3D: lateral traction along the row shown
    y: float = None          # 3D: the row's y (mm) and index
    row: int = None


def friction_law(case):
    """mu(|v_s|) of the case's friction law (docs/case-file.md, friction) as a function of
    the slip speed in mm/s, or None for Coulomb."""
    fr = case.get("friction") if isinstance(case, dict) else None
    law = fr.get("law", "coulomb") if isinstance(fr, dict) else "coulomb"
    if law in (None, "coulomb"):
        return None

    def listed(v):
        return [float(x) for x in (v if isinstance(v, list) else [v])]

    if law == "polach":
        ms, a, b = float(fr["mu_static"]), float(fr["A"]), float(fr["B"])
        return lambda s: ms * ((1 - a) * np.exp(-b * np.abs(s)) + a)
    mk, ex, vh = float(fr["mu_kinetic"]), listed(fr["mu_excess"]), listed(fr["half_velocity"])

    def mu(s):
        s = np.abs(np.asarray(s, dtype=np.float64))
        out = mk + 0 * s
        for i, (d, v) in enumerate(zip(ex, vh)):
            if law == "exponential":
                out = out + d * np.exp(-np.log(2) * s / v)
            elif law == "linear":
                out = out + d * np.maximum(0, 1 - s / (2 * v))
            elif i == 0:
                out = out + d / (1 + s / v)
            else:
                out = out + d / (1 + (s / v) ** 2)
        return out
    return mu


@dataclass
class FrictionProfile:
    """mu of every cell (the file's mu field) and its slip speed |v_s| at one record."""
    index: int
    time: float
    x: np.ndarray
    mu: np.ndarray
    slip_speed: np.ndarray  # mm/s
    law: object             # mu(|v_s|), or None
    law_name: str
    y: np.ndarray = None    # 3D: cell centres along y; mu and slip_speed are then (ny, nx)


def friction_profile(run, index):
    if not run.has("mu"):
        raise PostError(f"{run.path}: no field mu (written by rollsim run when friction.law is "
                        "not coulomb)")
    three = run.is_3d()
    names = ("slip_x", "slip_y") if three else ("slip",)
    if not all(run.has(n) for n in names):
        raise PostError(f"{run.path}: no field {' and '.join(names)} (list slip in output.fields)")
    V = float(run.variable("velocity")[index])

    def field(name):
        return np.ma.filled(np.ma.asarray(run.variable(name)[index], np.float64), np.nan)

    # the slip field is the relative slip v_s / V (docs/file-format.md); |v_s| in mm/s
    slip = np.hypot(field("slip_x"), field("slip_y")) if three else np.abs(field("slip"))
    case = run.case()
    return FrictionProfile(
        index=int(index), time=float(run.variable("time")[index]), x=run.values("x"),
        mu=field("mu"), slip_speed=slip * V if V > 0 else slip, law=friction_law(case),
        law_name=str(case.get("friction", {}).get("law", "coulomb")),
        y=run.values("y") if three else None)


def traction_profile(run, index, mu=None):
    """The TractionProfile of record `index`; mu from the case attribute unless given; with a
    velocity-dependent law (the file holds the field mu) the bound is each cell's mu p_n."""
    if mu is None and run.has("mu"):
        prof = traction_profile(run, index, mu=float("nan"))
        field = np.ma.filled(np.ma.asarray(run.variable("mu")[index, :], np.float64), np.nan)
        prof.g = np.where(prof.pn > 0, field * prof.pn, 0.0)
        return prof
    mu = run.mu() if mu is None else float(mu)
    px = run.variable("px")[index, :]
    pn = run.variable("pn")[index, :]
    prof = TractionProfile(
        index=int(index),
        time=float(run.variable("time")[index]),
        mu=mu,
        x=run.values("x"),
        px=np.ma.filled(np.ma.asarray(px, dtype=np.float64), np.nan),
        pn=np.ma.filled(np.ma.asarray(pn, dtype=np.float64), np.nan),
        g=None,
    )
    prof.g = mu * prof.pn
    if run.has("tauc"):
        prof.tauc = np.ma.filled(np.ma.asarray(run.variable("tauc")[index, :], np.float64), np.nan)
    if run.has("regime"):
        prof.regime = np.ma.filled(np.ma.asarray(run.variable("regime")[index, :]), -1).astype(int)
        prof.regime_flags = run.regime_flags()
    return prof


# ---- x-t maps ------------------------------------------------------------------------------


@dataclass
class FieldMap:
    """A (time, x) field with cell and record edges, ready for pcolormesh."""
    name: str
    units: str
    long_name: str
    x_edges: np.ndarray
    t_edges: np.ndarray
    values: np.ndarray  # (n_time, n_x)
    x: np.ndarray = None  # (n_x,) cell centres, mm
    t: np.ndarray = None  # (n_time,) record times, s


def field_map(run, name):
    run.require_records()
    dims = run.dims(name)
    if dims != ("time", "x"):
        raise PostError(f"{run.path}: variable '{name}' has dimensions {dims}, expected (time, x)")
    x, t = run.values("x"), run.values("time")
    return FieldMap(name, run.units(name), run.long_name(name), cell_edges(x), cell_edges(t),
                    run.values(name), x, t)


def regime_map(run):
    """Regime over (time, x) as integers (-1 where not stored) plus its flags."""
    fmap = field_map(run, "regime")
    fmap.values = np.where(np.isnan(fmap.values), -1, fmap.values).astype(int)
    return fmap, run.regime_flags()


# ---- time histories ------------------------------------------------------------------------

HISTORY_VARIABLES = ["time", "traction_coefficient", "creepage", "velocity", "n_exterior",
                     "n_adhesion", "n_slip", "n_plastic", "frictional_power", "plastic_power"]


def history(run):
    """The scalar time histories the history figure shows, by variable name, plus units."""
    run.require_records()
    data = {name: run.values(name) for name in HISTORY_VARIABLES}
    units = {name: run.units(name) for name in HISTORY_VARIABLES}
    return data, units


# ---- creep curves --------------------------------------------------------------------------

CREEPAGE_KEY = "rolling.creepage"


@dataclass
class CreepSeries:
    """One line of a creep curve: traction coefficient against creepage, sorted by creepage."""
    label: str
    creepage: np.ndarray
    traction: np.ndarray
    sources: list = field(default_factory=list)  # one "file" or "file[i,j]" per point
    values: dict = field(default_factory=dict)   # sweep files: the other swept keys' values
    elastic: bool = False                        # sweep files: the yield limit is never reached
    t_max: object = None                         # sweep files with temperature: T_max per point
    error: np.ndarray = None                     # sweep files: the estimated error of traction

    def sort(self):
        order = np.argsort(self.creepage, kind="stable")
        self.creepage = self.creepage[order]
        self.traction = self.traction[order]
        if self.t_max is not None:
            self.t_max = self.t_max[order]
        if self.error is not None:
            self.error = self.error[order]
        self.sources = [self.sources[i] for i in order]
        return self


def single_run_point(run):
    """(creepage, traction coefficient) at the last stored record of a single-run file."""
    run.require_records()
    creepage = float(run.variable("creepage")[-1])
    traction = float(run.variable("traction_coefficient")[-1])
    return creepage, traction


def _fmt(value):
    return f"{value:g}" if isinstance(value, (float, int, np.floating, np.integer)) else str(value)


def sweep_series(run, prefix=None, var="traction_coefficient", x_key=CREEPAGE_KEY):
    """Series from a sweep file: the dimension of `x_key` (rolling.creepage) is the abscissa,
    every combination of the other swept keys is one series, in the file's coordinate order.
    If `var` also has a time dimension the last record is used. Points that are missing (fill
    values, e.g. failed sweep points) are dropped."""
    dims = list(run.dims(var))
    values = run.values(var)
    if "time" in dims:
        values = np.take(values, -1, axis=dims.index("time"))
        dims.remove("time")
    x_dim = None
    for d in dims:
        if run.sweep_key(d) == x_key or d == x_key.replace(".", "_"):
            x_dim = d
    if x_dim is None:
        swept = ", ".join(run.sweep_key(d) for d in dims) or "none"
        hint = " (a 3D sweep: creep3d draws F_x, F_y, M_z against each creepage)" \
            if run.has("Fy") else ""
        raise PostError(f"{run.path}: sweep file does not sweep {x_key} (swept keys: {swept}); "
                        f"creepcurve needs {x_key} as a sweep dimension{hint}")
    creepage = run.coordinate(x_dim)
    others = [d for d in dims if d != x_dim]
    # Move the creepage axis last so each series is values[combination of others, :].
    values = np.moveaxis(values, dims.index(x_dim), -1)
    values = values.reshape([len(run.ds.dimensions[d]) for d in others] + [creepage.size])
    t_max = None  # the surface temperature per point (a temperature: block), same layout
    if var == "traction_coefficient" and run.has("T_max") and list(run.dims("T_max")) == dims:
        t_max = np.moveaxis(run.values("T_max"), dims.index(x_dim), -1).reshape(values.shape)
    # the traction coefficient's error estimate (steady sweeps, docs/file-format.md)
    errors = None
    if var == "traction_coefficient" and run.has("traction_coefficient_error") and \
            list(run.dims("traction_coefficient_error")) == dims:
        errors = np.moveaxis(run.values("traction_coefficient_error"), dims.index(x_dim), -1)
        errors = errors.reshape(values.shape)
    coords = {d: run.coordinate(d) for d in others}
    series = []
    for combo in itertools.product(*[range(len(coords[d])) for d in others]):
        parts = [f"{run.sweep_key(d)} = {_fmt(coords[d][i])}" for d, i in zip(others, combo)]
        label = ", ".join(parts) if parts else (prefix or run.title or os.path.basename(run.path))
        if parts and prefix:
            label = f"{prefix}: {label}"
        y = values[combo]
        ok = ~np.isnan(y) & ~np.isnan(creepage)
        idx = [f"{run.path}[{','.join(str(i) for i in combo + (k,))}]" for k in range(y.size)]
        s = CreepSeries(label, creepage[ok].copy(), y[ok].copy(), [s for s, k in zip(idx, ok) if k])
        if t_max is not None:
            s.t_max = np.asarray(t_max[combo], dtype=float)[ok].copy()
        if errors is not None:
            s.error = np.asarray(errors[combo], dtype=float)[ok].copy()
        s.values = {run.sweep_key(d): float(coords[d][i]) for d, i in zip(others, combo)}
        s.elastic = sweep.is_elastic(run, sweep.Point(tuple(combo), dict(s.values)))
        series.append(s.sort())
    return series


def creep_series(paths, labels=None, group_by=None):
    """Creep-curve series from single-run and sweep files.

    Single-run files give one point each (last record); files with the same label form one series.
    The label is, in order of precedence: labels[i] (labels holds one label for all files or one per
    file), "KEY = value" of the case key `group_by`, the file's title, the file name. Series appear
    in the order of their first file; with group_by they are sorted by the key's value instead.
    A sweep file contributes its own series (see sweep_series), with labels[i] as a prefix.
    Points in each series are sorted by creepage."""
    labels = list(labels or [])
    if labels and len(labels) not in (1, len(paths)):
        raise PostError(f"--label given {len(labels)} times for {len(paths)} files: "
                        "give it once (all files) or once per file")
    series = []  # in order of first appearance
    by_label = {}
    group_values = {}
    for i, path in enumerate(paths):
        label = labels[i] if len(labels) == len(paths) else (labels[0] if labels else None)
        value = None
        with RunFile(path) as run:
            if run.is_sweep():
                series.extend(sweep_series(run, prefix=label))
                continue
            creepage, traction = single_run_point(run)
            if label is None and group_by:
                value = case_value(run.case(), group_by)
                label = f"{group_by} = {_fmt(value) if value is not None else '(default)'}"
            if label is None:
                label = run.title or os.path.basename(path)
        if label not in by_label:
            by_label[label] = CreepSeries(label, np.empty(0), np.empty(0), [])
            series.append(by_label[label])
            if group_by:
                group_values[label] = value
        s = by_label[label]
        s.creepage = np.append(s.creepage, creepage)
        s.traction = np.append(s.traction, traction)
        s.sources.append(path)
    for s in series:
        s.sort()
    if group_by and not labels:
        def numeric(label):
            v = group_values.get(label)
            return (0, float(v), "") if isinstance(v, (int, float)) else (1, 0.0, str(v))
        series.sort(key=lambda s: numeric(s.label))
    return series


# ---- CSV export ----------------------------------------------------------------------------


def export_table(run, names):
    """Columns for a CSV of the variables `names`.

    The rows run over every combination of the dimensions the variables use, in the file's
    dimension order (time before x), the last dimension varying fastest. The first columns hold
    the coordinate values of those dimensions (coordinate variable, else the index), then one
    column per variable, broadcast over the dimensions it lacks. So time-only variables give one
    row per record (time, a, b, ...), (time, x) variables give the long format (time, x, value).
    Returns (header, columns), each column a masked array of the stored type."""
    if not names:
        raise PostError("export: no variables given (--var NAME...)")
    # Row dimensions in file order, unless that contradicts the variable with the most
    # dimensions (3D fields are (time, y, x) whichever of y and x the file defined first).
    order = list(run.ds.dimensions)
    used = set()
    widest = ()
    for name in names:
        used.update(run.dims(name))
        if len(run.dims(name)) > len(widest):
            widest = run.dims(name)
    row_dims = [d for d in order if d in used]
    if [d for d in row_dims if d in widest] != list(widest):
        row_dims = list(widest) + [d for d in row_dims if d not in widest]
    shape = [len(run.ds.dimensions[d]) for d in row_dims]
    grids = dict(zip(row_dims, (g.ravel() for g in np.indices(shape)))) if row_dims else {}
    nrows = int(np.prod(shape)) if row_dims else 1

    header, columns = [], []
    for d in row_dims:
        var = run.ds.variables.get(d)
        coord = run.raw(d) if var is not None and tuple(var.dimensions) == (d,) else \
            np.ma.asarray(np.arange(shape[row_dims.index(d)]))
        header.append(d)
        columns.append(coord[grids[d]])
    for name in dict.fromkeys(names):  # keep order, drop repeats
        if name in row_dims:
            continue  # already a coordinate column
        data = run.raw(name)
        dims = run.dims(name)
        if dims:
            col = data[tuple(grids[d] for d in dims)]
        else:
            col = np.ma.resize(data, nrows)
        header.append(name)
        columns.append(col)
    return header, columns


def _cell(value, masked):
    if masked:
        return ""
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back to the same double
    return str(value)


def write_csv(out, header, columns):
    """Write the table to the path `out` ('-' = stdout). Floats are written with repr(), which
    reads back to the identical double; missing values are empty cells."""
    cols = [(np.ma.getdata(c).tolist(), np.ma.getmaskarray(c).tolist()) for c in columns]
    nrows = len(cols[0][0]) if cols else 0
    f = sys.stdout if out == "-" else open(out, "w", newline="")
    try:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in range(nrows):
            w.writerow([_cell(v[r], m[r]) for v, m in cols])
    finally:
        if f is not sys.stdout:
            f.close()
    return nrows


class RigResults:
    """Twin-disc summaries of a rollsim run (twin_disc: block): per protocol step and
    per revolution of disc 1. Steps or revolutions not reached are NaN (dropped)."""

    def __init__(self, step_slip, step_mu, rev_index, rev_slip, rev_mu, rev_temperature=None):
        self.step_slip, self.step_mu = step_slip, step_mu
        self.rev_index, self.rev_slip, self.rev_mu = rev_index, rev_slip, rev_mu
        # with a temperature: block, {variable name: per revolution} (revolution_T_max, the
        # inlet temperatures, the bulk temperatures with disc_mass), else None
        self.rev_temperature = rev_temperature


def rig_results(run):
    """Read the twin-disc summaries (step_* and revolution_* variables)."""
    if not run.has("step_traction_coefficient"):
        raise PostError(f"{run.path}: no twin-disc results (variable "
                        "'step_traction_coefficient'): not a twin_disc: run")
    step_slip = np.asarray(run.values("step_slip"), dtype=float)
    step_mu = np.asarray(run.values("step_traction_coefficient"), dtype=float)
    rev_slip = np.asarray(run.values("revolution_slip"), dtype=float)
    rev_mu = np.asarray(run.values("revolution_traction_coefficient"), dtype=float)
    done = np.isfinite(step_mu)
    rev_done = np.isfinite(rev_mu)
    if not rev_done.any():
        raise PostError(f"{run.path}: no revolution completed yet")
    temps = None
    if run.has("revolution_T_max"):
        names = ["revolution_T_max", "revolution_inlet_temperature_1",
                 "revolution_inlet_temperature_2", "revolution_bulk_temperature_1",
                 "revolution_bulk_temperature_2"]
        temps = {n: np.asarray(run.values(n), dtype=float)[rev_done] for n in names if run.has(n)}
    return RigResults(step_slip[done], step_mu[done], np.nonzero(rev_done)[0] + 1,
                      rev_slip[rev_done], rev_mu[rev_done], temps)
