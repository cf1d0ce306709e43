"""Sweep files (rollsim sweep): the swept keys, their points, and the profiles stored per point.

A sweep file has one dimension per swept key (the dimensions of `traction_coefficient`, in file
order, the last varying fastest); with output.fields it also holds the profiles px, pn, tauc, ...
over (swept keys..., x). A *point* is one combination of the swept values; its values of keys that
are not swept come from the file's `case` attribute (the YAML as run), else the defaults of docs/case-file.md.
"""
import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from . import PostError
from .runfile import case_value

# docs/case-file.md: defaults of the keys figures need when a case does not give them.
CASE_DEFAULTS = {
    "friction.mu": 0.5,
    "contact.normal_load": 178.9,
    "contact.radius": 500.0,
    "material.shear_modulus": 82000.0,
    "material.poisson_ratio": 0.28,
    "plasticity.tau_c0": 35.0,
}

# How figures name swept keys: (symbol, unit shown, factor from the file's value).
KEY_NAMES = {
    "rolling.creepage": ("ξ", "%", 100.0),
    "rolling.lateral_creepage": ("η", "", 1.0),
    "rolling.spin": ("φ", "1/mm", 1.0),
    "plasticity.k_rel": ("k_rel", "", 1.0),
    "plasticity.k_tau": ("k_τ", "N/mm³", 1.0),
    "plasticity.tau_c0": ("τ_c0", "N/mm²", 1.0),
    "plasticity.tau_c_min": ("τ_c,min", "N/mm²", 1.0),
    "friction.mu": ("μ", "", 1.0),
    "contact.normal_load": ("q", "N/mm", 1.0),
    "layer.thickness": ("h₃", "mm", 1.0),
}


def describe(key, value, units=""):
    """'ξ = -0.3 %', 'k_rel = 0.6', or 'KEY = value UNITS' for keys without a symbol."""
    name, unit, factor = KEY_NAMES.get(key, (key, "" if units in ("", "1") else units, 1.0))
    if key == "contact.normal_load" and units == "N":  # a 3D load: the total force
        name, unit = "F_n", "N"
    return f"{name} = {value * factor:.6g}{' ' + unit if unit else ''}"


@dataclass
class Point:
    """One sweep point: its index into the swept dimensions and the swept values by key."""
    index: tuple
    values: dict  # dotted key -> value, in the file's dimension order
    dims: list = field(default_factory=list)

    def label(self, run, keys=None):
        keys = list(self.values) if keys is None else keys
        return ", ".join(describe(k, self.values[k], sweep_units(run, k)) for k in keys)


def sweep_dims(run):
    """The swept dimensions (those of traction_coefficient), in file order."""
    return [d for d in run.dims("traction_coefficient") if d != "time"]


def sweep_units(run, key):
    for d in sweep_dims(run):
        if run.sweep_key(d) == key:
            return run.units(d)
    return ""


def key_dim(run, key):
    """The dimension of a swept dotted key (PostError listing the swept keys if not swept)."""
    dims = sweep_dims(run)
    for d in dims:
        if run.sweep_key(d) == key or d == key.replace(".", "_"):
            return d
    swept = ", ".join(run.sweep_key(d) for d in dims)
    raise PostError(f"{run.path}: {key} is not swept in this file (swept keys: {swept})")


def points(run, select=None):
    """Every point in file order (the last key fastest), restricted by `select`: a dict of
    dotted key -> value keeping the points whose coordinate is nearest to that value."""
    dims = sweep_dims(run)
    coords = [run.coordinate(d) for d in dims]
    keep = [range(len(c)) for c in coords]
    for key, wanted in (select or {}).items():
        d = key_dim(run, key)
        i = dims.index(d)
        keep[i] = [int(np.argmin(np.abs(coords[i] - float(wanted))))]
    out = []
    for idx in itertools.product(*keep):
        out.append(Point(tuple(idx), {run.sweep_key(d): float(c[i])
                                      for d, c, i in zip(dims, coords, idx)}, dims))
    return out


def value_at(run, point, key):
    """Value of `key` at a point: swept value, else the case attribute, else the default."""
    if key in point.values:
        return point.values[key]
    v = case_value(run.case(), key)
    if v is None:
        return CASE_DEFAULTS.get(key)
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def has_plasticity(run):
    return isinstance(run.case().get("plasticity"), dict)


def hertz_peak_pressure(run, point):
    """p0 = 2q/(pi a), a = sqrt(4 q R (1 - nu)/(pi G)) (docs/verification.md 1) at a point."""
    q = value_at(run, point, "contact.normal_load")
    r = value_at(run, point, "contact.radius")
    g = value_at(run, point, "material.shear_modulus")
    nu = value_at(run, point, "material.poisson_ratio")
    a = math.sqrt(4.0 * q * r * (1.0 - nu) / (math.pi * g))
    return 2.0 * q / (math.pi * a)


def is_elastic(run, point, pn=None):
    """True when the yield limit is never reached at this point, so the result is the elastic
    one: no plasticity block, or tau_c0 >= mu max p_n (|p| <= g = mu p_n always, so tau_c stays
    tau_c0 and no cell can yield). max p_n from the stored pressure, else Hertz's p0."""
    if not has_plasticity(run):
        return True
    tau_c0 = value_at(run, point, "plasticity.tau_c0")
    mu = value_at(run, point, "friction.mu")
    if run.has("mu"):  # velocity-dependent friction: the largest mu of the point's cells
        mu = float(np.nanmax(field_at(run, "mu", point)))
    if pn is not None and np.size(pn):
        p_max = float(np.nanmax(pn))
    else:
        try:
            p_max = hertz_peak_pressure(run, point)
        except TypeError:  # 3D case (radius: [Rx, Ry]): the line-contact formula does not apply
            return False
    return tau_c0 >= mu * p_max


def field_at(run, name, point):
    """Profile `name` of a point as float64 (fill/NaN where missing)."""
    var = run.variable(name)
    dims = tuple(var.dimensions)
    if dims[-1] != "x" or [d for d in dims[:-1]] != point.dims:
        raise PostError(f"{run.path}: variable '{name}' has dimensions {dims}, expected the swept "
                        f"keys and x {tuple(point.dims) + ('x',)}")
    data = var[point.index + (slice(None),)]
    return np.ma.filled(np.ma.asarray(data, dtype=np.float64), np.nan)


def require_profiles(run, names=("px", "pn")):
    missing = [n for n in names if not run.has(n)]
    if missing:
        raise PostError(f"{run.path}: sweep file without the profiles {', '.join(missing)}: run the "
                        "sweep with output.fields listing them, e.g. [px, pn, tauc, regime]")


@dataclass
class SweepProfile:
    """p_x, g = mu p_n, tau_c (None when elastic) and regimes of one sweep point."""
    point: Point
    mu: float
    x: np.ndarray
    px: np.ndarray
    pn: np.ndarray
    g: np.ndarray
    tauc: np.ndarray = None
    regime: np.ndarray = None
    regime_flags: tuple = None
    elastic: bool = False


def sweep_profile(run, point, mu=None):
    px, pn = field_at(run, "px", point), field_at(run, "pn", point)
    elastic = is_elastic(run, point, pn)
    if mu is None and run.has("mu"):  # each cell's bound mu(|v_s|) p_n
        g = np.where(pn > 0, field_at(run, "mu", point) * pn, 0.0)
        prof = SweepProfile(point, float("nan"), run.values("x"), px, pn, g, elastic=elastic)
    else:
        mu = value_at(run, point, "friction.mu") if mu is None else float(mu)
        prof = SweepProfile(point, mu, run.values("x"), px, pn, mu * pn, elastic=elastic)
    if run.has("tauc") and not elastic:
        prof.tauc = field_at(run, "tauc", point)
    if run.has("regime"):
        r = field_at(run, "regime", point)
        prof.regime = np.where(np.isnan(r), -1, r).astype(int)
        prof.regime_flags = run.regime_flags()
    return prof


def group(points_, run, overlay=None):
    """Panels: with `overlay` KEY, one panel per combination of the other swept keys holding the
    points along KEY (in file order); without, one panel per point."""
    if overlay is None:
        return [[p] for p in points_]
    key_dim(run, overlay)  # PostError if not swept
    panels = {}
    for p in points_:
        rest = tuple((k, v) for k, v in p.values.items() if k != overlay)
        panels.setdefault(rest, []).append(p)
    return list(panels.values())
