"""3D (elliptic contact) files: fields over the patch, its outline, and creep curves in F_x, F_y, M_z.

A 3D run file (docs/file-format.md, "Run files") has dimensions time, y, x with coordinate variables
x, y (cell centres, mm) and fields over (time, y, x): px, py, pn, slip_x, slip_y, upl_x, upl_y,
ustar, tauc, regime. A 3D sweep file with output.fields holds them over (swept keys..., y, x).
Where a record index is taken, a sweep.Point (one sweep point) may be given instead. Nothing here draws; plots.py draws what these functions return.
"""
import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from . import PostError
from .extract import sweep_series

# --field choices of the map figure: the colour and, for vector fields, the arrows.
#   name: (colour variable(s), arrow components or None, symbol, description)
MAP_FIELDS = {
    "traction": (("px", "py"), ("px", "py"), "|p|", "tangential traction"),
    "slip": (("slip_x", "slip_y"), ("slip_x", "slip_y"), "|s|", "slip velocity"),
    "pressure": (("pn",), None, "p_n", "pressure"),
    "regime": (("regime",), None, "regime", "contact regime"),
    "ustar": (("ustar",), None, "u*", "accumulated plastic deformation"),
    "tauc": (("tauc",), None, "τ_c", "yield limit"),
    "upl": (("upl_x", "upl_y"), ("upl_x", "upl_y"), "|u_pl|", "plastic displacement"),
    "T1": (("T1",), None, "T_1", "surface temperature of body 1"),
    "T2": (("T2",), None, "T_2", "surface temperature of body 2"),
}

CREEP_KEYS = ("rolling.creepage", "rolling.lateral_creepage", "rolling.spin")
CREEP_SYMBOLS = {"rolling.creepage": "ξ", "rolling.lateral_creepage": "η",
                 "rolling.spin": "φ"}
FORCE_SYMBOLS = {"Fx": "F_x", "Fy": "F_y", "Mz": "M_z"}


@dataclass
class Ellipse:
    """An ellipse outline of the patch: centre (xc, yc), semi-axes a (along x), b (along y)."""
    xc: float
    yc: float
    a: float
    b: float
    source: str  # "Hertz" (file attributes) or "fitted" (second moments of the contact cells)

    def polygon(self, n=181):
        t = np.linspace(0.0, 2.0 * np.pi, n)
        return self.xc + self.a * np.cos(t), self.yc + self.b * np.sin(t)


@dataclass
class FieldMap3D:
    """One record of a 3D field: colour values (ny, nx), optional arrows, the contact cells."""
    index: object            # record index (run file) or sweep.Point
    time: float              # None for a sweep point
    field: str
    symbol: str
    long_name: str
    units: str
    x: np.ndarray            # (nx,) cell centres, mm
    y: np.ndarray            # (ny,)
    values: np.ndarray       # (ny, nx) colour values (regime: int codes, -1 missing)
    contact: np.ndarray      # (ny, nx) bool: cells in contact (pn > 0, else regime != exterior)
    ellipse: Ellipse = None
    vx: np.ndarray = None    # (ny, nx) arrow components, or None
    vy: np.ndarray = None
    regime_flags: tuple = None
    label: str = ""          # panel title of a sweep point


def _filled(a, fill=np.nan):
    return np.ma.filled(np.ma.asarray(a, dtype=np.float64), fill)


def _leading(index):
    """(expected leading dimensions, index tuple) of a record index or a sweep point."""
    if isinstance(index, (int, np.integer)):
        return ("time",), (int(index),)
    return tuple(index.dims), tuple(index.index)


def check_field_dims(run, name, index=0):
    dims = run.dims(name)
    lead, _ = _leading(index)
    if dims != lead + ("y", "x"):
        raise PostError(f"{run.path}: variable '{name}' has dimensions {dims}, expected "
                        f"{lead + ('y', 'x')}")


def record_field(run, name, index):
    """Field `name` of record `index` (or at a sweep point) as float64 (ny, nx); NaN where
    missing."""
    check_field_dims(run, name, index)
    _, idx = _leading(index)
    return _filled(run.variable(name)[idx + (slice(None), slice(None))])


def contact_cells(run, index):
    """Cells in contact at a record: p_n > 0 when pn is stored, else regime != exterior."""
    if run.has("pn"):
        pn = record_field(run, "pn", index)
        return np.nan_to_num(pn) > 0.0
    if run.has("regime"):
        values, meanings = run.regime_flags()
        exterior = [v for v, m in zip(values, meanings) if m == "exterior"]
        r = record_field(run, "regime", index)
        return ~np.isnan(r) & ~np.isin(r, exterior)
    raise PostError(f"{run.path}: neither pn nor regime stored: the contact area is unknown "
                    "(output.fields should list pn)")


def cell_size(c):
    c = np.asarray(c, dtype=np.float64)
    return float(np.mean(np.diff(c))) if c.size > 1 else 0.0


def fit_ellipse(x, y, contact):
    """The ellipse with the same centroid and second moments as the contact cells: for a uniform
    ellipse <(x - xc)^2> = a^2/4 over its area, so a = 2 sqrt(<(x - xc)^2>), each cell counted
    with its own second moment dx^2/12 (b likewise). The recovered semi-axes are within a cell
    of the discrete patch's. None when no cell is in contact."""
    if not np.any(contact):
        return None
    X, Y = np.meshgrid(x, y)
    xs, ys = X[contact], Y[contact]
    dx, dy = cell_size(x), cell_size(y)
    xc, yc = float(xs.mean()), float(ys.mean())
    a = 2.0 * math.sqrt(float(np.mean((xs - xc) ** 2)) + dx * dx / 12.0)
    b = 2.0 * math.sqrt(float(np.mean((ys - yc) ** 2)) + dy * dy / 12.0)
    return Ellipse(xc, yc, a, b, "fitted")


def hertz_ellipse(run, index=None):
    """Hertz's ellipse of a record or sweep point, if the file says it: a sweep point's
    variables hertz_a, hertz_b (mm); else the global attributes hertz_a, hertz_b at the load
    hertz_load, scaled to the record's F_n as F^(1/3) (a and b grow so at fixed curvatures and
    materials; files without hertz_load: as they are)."""
    try:
        if index is not None and not isinstance(index, (int, np.integer)) and \
                run.has("hertz_a") and run.has("hertz_b"):
            _, idx = _leading(index)
            a, b = (float(_filled(run.variable(v)[idx])) for v in ("hertz_a", "hertz_b"))
            return Ellipse(0.0, 0.0, a, b, "Hertz") if a > 0 and b > 0 else None
        a, b = run.attr("hertz_a"), run.attr("hertz_b")
        if a is None or b is None:
            return None
        a, b = float(np.ravel(a)[0]), float(np.ravel(b)[0])
        load = run.attr("hertz_load")
        if load is not None and isinstance(index, (int, np.integer)) and run.has("Fn"):
            fn = float(_filled(run.variable("Fn")[int(index)]))
            scale = (fn / float(np.ravel(load)[0])) ** (1.0 / 3.0)
            if np.isfinite(scale) and scale > 0:
                a, b = a * scale, b * scale
        return Ellipse(0.0, 0.0, a, b, "Hertz")
    except (TypeError, ValueError, IndexError):
        return None


def contact_edges(x, y, contact):
    """The discrete contact edge: cell sides between a cell in contact and one outside (or the
    grid's border), as a list of segments ((x0, y0), (x1, y1)) in mm."""
    dx, dy = cell_size(x) or 1.0, cell_size(y) or 1.0
    ny, nx = contact.shape
    pad = np.zeros((ny + 2, nx + 2), dtype=bool)
    pad[1:-1, 1:-1] = contact
    segs = []
    jj, ii = np.nonzero(contact)
    for j, i in zip(jj.tolist(), ii.tolist()):
        x0, x1 = x[i] - dx / 2, x[i] + dx / 2
        y0, y1 = y[j] - dy / 2, y[j] + dy / 2
        # neighbours of cell (j, i) sit at (j + 1 +- 1, i + 1 +- 1) in the padded grid
        if not pad[j, i + 1]:
            segs.append(((x0, y0), (x1, y0)))   # below
        if not pad[j + 2, i + 1]:
            segs.append(((x0, y1), (x1, y1)))   # above
        if not pad[j + 1, i]:
            segs.append(((x0, y0), (x0, y1)))   # left
        if not pad[j + 1, i + 2]:
            segs.append(((x1, y0), (x1, y1)))   # right
    return segs


def field_map(run, field, index):
    """The FieldMap3D of `field` (a MAP_FIELDS key) at record `index`."""
    if field not in MAP_FIELDS:
        raise PostError(f"--field {field}: expected one of {', '.join(MAP_FIELDS)}")
    colour, arrows, symbol, description = MAP_FIELDS[field]
    missing = [v for v in colour if not run.has(v)]
    if missing:
        raise PostError(f"{run.path}: no variable {' or '.join(repr(m) for m in missing)}: the "
                        f"{field} map needs {', '.join(colour)} (output.fields)")
    comps = [record_field(run, v, index) for v in colour]
    if len(comps) == 2:
        values = np.hypot(comps[0], comps[1])
    else:
        values = comps[0]
    contact = contact_cells(run, index)
    x, y = run.values("x"), run.values("y")
    time = float(run.variable("time")[index]) if isinstance(index, (int, np.integer)) else None
    m = FieldMap3D(index=index, time=time, field=field,
                   symbol=symbol, long_name=description, units=run.units(colour[0]), x=x, y=y,
                   values=values, contact=contact)
    if field == "regime":
        m.values = np.where(np.isnan(values), -1, values).astype(int)
        m.regime_flags = run.regime_flags()
        m.units = ""
    if arrows:
        m.vx, m.vy = comps[0], comps[1]
    m.ellipse = hertz_ellipse(run, index) or fit_ellipse(x, y, contact)
    return m


def row_profile(run, index, y_wanted, mu=None):
    """An extract.TractionProfile along x at the row of cells nearest to y_wanted (mm) at record
    `index`: p_x, p_y, g = mu p_n, tau_c and regimes of that row."""
    from .extract import TractionProfile
    for name in ("px", "py", "pn"):
        run.variable(name)
    y = run.values("y")
    row = int(np.argmin(np.abs(y - float(y_wanted))))
    mu = run.mu() if mu is None else float(mu)
    pn = record_field(run, "pn", index)[row]
    prof = TractionProfile(index=int(index), time=float(run.variable("time")[index]), mu=mu,
                           x=run.values("x"), px=record_field(run, "px", index)[row], pn=pn,
                           g=mu * pn, py=record_field(run, "py", index)[row], y=float(y[row]),
                           row=row)
    if run.has("tauc"):
        prof.tauc = record_field(run, "tauc", index)[row]
    if run.has("regime"):
        r = record_field(run, "regime", index)[row]
        prof.regime = np.where(np.isnan(r), -1, r).astype(int)
        prof.regime_flags = run.regime_flags()
    return prof


def arrow_cells(m, max_arrows):
    """Cells that get an arrow: in contact, on a lattice of every k-th cell (k chosen so at most
    `max_arrows` arrows lie along x and along y), the lattice through the centre cell."""
    ny, nx = m.contact.shape
    step = max(1, math.ceil(max(nx, ny) / max(1, int(max_arrows))))
    ic, jc = nx // 2, ny // 2
    keep = np.zeros_like(m.contact)
    keep[np.ix_((np.arange(ny) - jc) % step == 0, (np.arange(nx) - ic) % step == 0)] = True
    return keep & m.contact, step


# ---- time histories ------------------------------------------------------------------------

HISTORY_3D = ["Fy", "Mz", "Fn", "lateral_creepage", "spin"]


def history_extra(run):
    """The 3D scalars the history figure adds (Fy, Mz, Fn, lateral creepage, spin); missing
    ones (e.g. spin in an older file) are left out."""
    data = {name: run.values(name) for name in HISTORY_3D if run.has(name)}
    units = {name: run.units(name) for name in data}
    missing = [n for n in ("Fy", "Mz", "Fn") if n not in data]
    if missing:
        raise PostError(f"{run.path}: a 3D file without {', '.join(missing)}")
    return data, units


# ---- creep curves in F_x, F_y, M_z ---------------------------------------------------------

@dataclass
class CreepPanel:
    key: str        # swept creepage key (abscissa)
    var: str        # Fx, Fy or Mz
    units: str      # of var
    key_units: str  # of the key
    series: list    # extract.CreepSeries: x = the key's values, y = var
    series_units: dict = dataclasses.field(default_factory=dict)  # units of the keys labelling the series


MIN_CURVE_POINTS = 3


def creep3d_panels(run, names=("Fx", "Fy", "Mz"), x_keys=None):
    """One panel per (swept creepage key, force or moment): the key's values on the abscissa,
    one series per combination of the other swept keys (sweep_series), last record if timed.
    The abscissae: `x_keys` if given, else every swept creepage key with at least 3 values (a
    key swept over 2 values only labels the series), else every swept creepage key; in the
    order ξ, η, φ."""
    if not run.is_sweep():
        raise PostError(f"{run.path}: creep3d needs a sweep file (rollsim sweep) over "
                        f"{', '.join(CREEP_KEYS)}")
    if not run.is_3d():
        raise PostError(f"{run.path}: not a 3D sweep file (no Fy): use creepcurve")
    dims = [d for d in run.dims("traction_coefficient") if d != "time"]
    keys = [run.sweep_key(d) for d in dims]
    canonical = [k if k in CREEP_KEYS else k.replace("_", ".", 1) for k in keys]
    swept = [k for k in CREEP_KEYS if k in canonical]
    if not swept:
        raise PostError(f"{run.path}: sweeps none of {', '.join(CREEP_KEYS)} (swept keys: "
                        f"{', '.join(keys)})")
    if x_keys:
        for k in x_keys:
            if k not in swept:
                raise PostError(f"{run.path}: --x {k}: not a swept creepage (swept: "
                                f"{', '.join(swept)})")
        swept = [k for k in CREEP_KEYS if k in x_keys]
    else:
        long_ = [k for k in swept
                 if len(run.ds.dimensions[dims[canonical.index(k)]]) >= MIN_CURVE_POINTS]
        swept = long_ or swept
    panels = []
    units = {k: run.units(d) for k, d in zip(canonical, dims)}
    units.update({k: run.units(d) for k, d in zip(keys, dims)})
    for key in swept:
        dim = dims[canonical.index(key)]
        for name in names:
            series = sweep_series(run, var=name, x_key=key)
            panels.append(CreepPanel(key, name, run.units(name), run.units(dim), series, units))
    return panels
