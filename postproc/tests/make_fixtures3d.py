#!/usr/bin/python3
"""Synthetic 3D netCDF files with analytic content (docs/file-format.md, "Run files").

Usage: make_fixtures3d.py OUTDIR

  run3d.nc        a 3D run file: global attribute dimension = 3, dimensions time (3), y (NY), x (NX)
                  with cell-centre coordinates (a cell centred on x = y = 0); the Hertz pressure
                  p_n = P0 sqrt(1 - x^2/A^2 - y^2/B^2) and the traction p = MU p_n (-C_k, D_k (1 + x/2A)) at
                  record k; regimes, u*, tau_c, slip and plastic displacement as given by the
                  functions below; scalars Fx, Fy, Mz, Fn summed from the fields.
  run3d_hertz.nc  the same with the global attributes hertz_a = A, hertz_b = B.
  sweep3d.nc      a 3D sweep file over rolling_creepage (5) x rolling_lateral_creepage (3), Fx, Fy,
                  Mz from creep_forces(); one point missing (fill value).
  sweep3d_spin.nc a 3D sweep over friction_mu (2) x rolling_spin (4).
  sweep3d_fields.nc  a 3D sweep over rolling_creepage (XI_FIELDS) with the fields px, py, pn, regime
                  over (rolling_creepage, y, x): sweep_fields(xi).

check_post3d.py imports this module for the expected values.
"""
import os
import sys

import netCDF4
import numpy as np

A, B = 3.0, 2.0           # semi-axes, mm
P0 = 1000.0               # peak pressure, N/mm^2
MU = 0.3
NX, NY = 31, 25           # odd: a cell centre on x = 0 and on y = 0
DX, DY = 2.4 * A / NX, 2.4 * B / NY   # grid over +-1.2 A, +-1.2 B
TIMES = [0.0, 1.0e-4, 2.0e-4]
C = [0.2, 0.5, 0.8]       # p_x = -C_k MU p_n
D = [0.1, 0.2, 0.3]       # p_y = +D_k MU p_n
V = 30000.0

XI = [0.0, -0.0005, -0.001, -0.002, -0.004]
ETA = [-0.001, 0.0, 0.0015]
MISSING = (3, 2)
SPIN = [-0.02, -0.005, 0.005, 0.02]
MUS = [0.3, 0.2]
FN_SWEEP = 10000.0


def grid():
    x = (np.arange(NX) - (NX - 1) / 2) * DX
    y = (np.arange(NY) - (NY - 1) / 2) * DY
    return x, y


def pressure():
    x, y = grid()
    X, Y = np.meshgrid(x, y)
    return P0 * np.sqrt(np.maximum(0.0, 1.0 - X ** 2 / A ** 2 - Y ** 2 / B ** 2))


def fields(k):
    """Every field of record k, (NY, NX)."""
    x, y = grid()
    X, Y = np.meshgrid(x, y)
    pn = pressure()
    inside = pn > 0.0
    px = -C[k] * MU * pn
    py = D[k] * MU * pn * (1.0 + 0.5 * X / A)   # skewed: a non-zero spin moment
    regime = np.zeros(pn.shape, dtype=np.int8)
    regime[inside & (X > 0.0)] = 1                          # adhesion at the leading half
    regime[inside & (X <= 0.0)] = 2                         # slip at the trailing half
    regime[inside & (X <= 0.0) & (np.abs(Y) < 0.5)] = 3     # a plastic strip
    plastic = regime == 3
    ustar = np.where(plastic, 1e-4 * (k + 1) * (1.0 - X), 0.0)
    tauc = 150.0 + 2.0e4 * ustar
    slip = regime >= 2
    slip_x = np.where(slip, -50.0 * (k + 1) * (1.0 - X / A), 0.0)
    slip_y = np.where(slip, 20.0 * (k + 1), 0.0)
    upl_x = np.where(plastic, -ustar * 0.8, 0.0)
    upl_y = np.where(plastic, ustar * 0.6, 0.0)
    return dict(px=px, py=py, pn=pn, slip_x=slip_x, slip_y=slip_y, upl_x=upl_x, upl_y=upl_y,
                ustar=ustar, tauc=tauc, regime=regime)


def scalars(k):
    x, y = grid()
    X, Y = np.meshgrid(x, y)
    f = fields(k)
    da = DX * DY
    fx, fy, fn = f["px"].sum() * da, f["py"].sum() * da, f["pn"].sum() * da
    return dict(Fx=fx, Fy=fy, Fn=fn, Mz=float(((X * f["py"] - Y * f["px"]) * da).sum()),
                traction_coefficient=fx / fn, creepage=-1e-3 * (k + 1),
                lateral_creepage=5e-4 * (k + 1), spin=-0.001 * k, velocity=V,
                n_exterior=int((f["regime"] == 0).sum()), n_adhesion=int((f["regime"] == 1).sum()),
                n_slip=int((f["regime"] == 2).sum()), n_plastic=int((f["regime"] == 3).sum()),
                frictional_power=1.0e5 * (k + 1), plastic_power=2.0e3 * k,
                elastic_energy=1.0 * k)


FIELD_META = {
    "px": ("N/mm2", "tangential traction, x"), "py": ("N/mm2", "tangential traction, y"),
    "pn": ("N/mm2", "pressure"), "slip_x": ("mm/s", "slip velocity, x"),
    "slip_y": ("mm/s", "slip velocity, y"), "upl_x": ("mm", "plastic displacement, x"),
    "upl_y": ("mm", "plastic displacement, y"), "ustar": ("mm", "accumulated plastic deformation"),
    "tauc": ("N/mm2", "current yield limit"), "regime": ("1", "contact regime of the cell"),
}
SCALAR_UNITS = {"Fx": "N", "Fy": "N", "Fn": "N", "Mz": "N mm", "traction_coefficient": "1",
                "creepage": "1", "lateral_creepage": "1", "spin": "1/mm", "velocity": "mm/s",
                "frictional_power": "N mm/s", "plastic_power": "N mm/s", "elastic_energy": "N mm"}

CASE = f"""title: synthetic 3D
contact:
  dimension: 3
  normal_load: 10000.0
  radius: [500.0, 300.0]
grid:
  cells: [{NX}, {NY}]
friction:
  mu: {MU}
simulation:
  mode: transient
"""


def _globals(ds, title):
    ds.Conventions = "CF-1.10"
    ds.title = title
    ds.source = "rollsim_post test fixture"
    ds.history = "make_fixtures3d.py"
    ds.case = CASE
    ds.status = "complete"
    ds.dimension = np.int32(3)


def write_run(path, hertz=False):
    x, y = grid()
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, "synthetic 3D run: Hertz ellipse a = 3, b = 2 mm")
        if hertz:
            ds.hertz_a = A
            ds.hertz_b = B
        ds.createDimension("time", None)
        ds.createDimension("x", NX)   # x before y, as the 2D writer defines x first
        ds.createDimension("y", NY)
        for name, values, long_name in (("x", x, "cell centre, rolling direction"),
                                        ("y", y, "cell centre, lateral")):
            v = ds.createVariable(name, "f8", (name,))
            v.units, v.long_name = "mm", long_name
            v[:] = values
        t = ds.createVariable("time", "f8", ("time",))
        t.units = "s"
        t[:] = TIMES
        for name, (units, long_name) in FIELD_META.items():
            v = ds.createVariable(name, "i1" if name == "regime" else "f8", ("time", "y", "x"))
            v.units, v.long_name = units, long_name
            if name == "regime":
                v.flag_values = np.array([0, 1, 2, 3], dtype=np.int8)
                v.flag_meanings = "exterior adhesion slip plastic"
            for k in range(len(TIMES)):
                v[k] = fields(k)[name]
        for name in scalars(0):
            kind = "i4" if name.startswith("n_") else "f8"
            v = ds.createVariable(name, kind, ("time",))
            v.units = SCALAR_UNITS.get(name, "1")
            v.long_name = name
            v[:] = [scalars(k)[name] for k in range(len(TIMES))]


def creep_forces(xi, eta, spin=0.0, mu=MU):
    """Made-up smooth 3D creep forces (N, N mm), saturating at mu Fn."""
    fx = -mu * FN_SWEEP * np.tanh(xi / 0.001)
    fy = -mu * FN_SWEEP * np.tanh(eta / 0.001 + spin / 0.01)
    mz = 800.0 * eta / 0.001 - 4000.0 * spin / 0.01 + 50.0 * xi / 0.001
    return fx, fy, mz


def _axis(ds, key, values, units):
    name = key.replace(".", "_")
    ds.createDimension(name, len(values))
    v = ds.createVariable(name, "f8", (name,))
    v.key, v.units = key, units
    v[:] = values
    return name


def write_sweep(path, axes, func):
    """axes: [(key, values, units)]; func(point dict) -> (Fx, Fy, Mz) or None (missing)."""
    fill = netCDF4.default_fillvals["f8"]
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, f"synthetic 3D sweep over {', '.join(k for k, _, _ in axes)}")
        dims = tuple(_axis(ds, *a) for a in axes)
        shape = tuple(len(a[1]) for a in axes)
        out = {n: np.full(shape, np.nan) for n in ("Fx", "Fy", "Mz", "Fn",
                                                   "traction_coefficient")}
        for idx in np.ndindex(*shape):
            point = {a[0]: a[1][i] for a, i in zip(axes, idx)}
            r = func(point, idx)
            if r is None:
                continue
            out["Fx"][idx], out["Fy"][idx], out["Mz"][idx] = r
            out["Fn"][idx] = FN_SWEEP
            out["traction_coefficient"][idx] = r[0] / FN_SWEEP
        for name, values in out.items():
            v = ds.createVariable(name, "f8", dims, fill_value=fill)
            v.units = {"Mz": "N mm", "traction_coefficient": "1"}.get(name, "N")
            v[:] = np.ma.masked_invalid(values)
        n = ds.createVariable("n_slip", "i4", dims)
        n.units = "1"
        n[:] = np.zeros(shape, dtype=np.int32)


XI_FIELDS = [-0.0005, -0.001, -0.002]


def sweep_fields(xi):
    """Fields of a sweep point: the Hertz pressure, p = MU p_n tanh(xi/0.001) (1, -0.5), regime
    adhesion in front of x = 0 and slip behind."""
    x, y = grid()
    X, _ = np.meshgrid(x, y)
    pn = pressure()
    s = np.tanh(xi / 0.001)
    regime = np.where(pn > 0.0, np.where(X > 0.0, 1, 2), 0).astype(np.int8)
    return dict(px=MU * pn * s, py=-0.5 * MU * pn * s, pn=pn, regime=regime)


def write_sweep_fields(path):
    x, y = grid()
    da = DX * DY
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, "synthetic 3D sweep with fields")
        d = _axis(ds, "rolling.creepage", XI_FIELDS, "1")
        ds.createDimension("x", NX)
        ds.createDimension("y", NY)
        for name, values in (("x", x), ("y", y)):
            v = ds.createVariable(name, "f8", (name,))
            v.units = "mm"
            v[:] = values
        for name in ("px", "py", "pn", "regime"):
            v = ds.createVariable(name, "i1" if name == "regime" else "f8", (d, "y", "x"))
            v.units = FIELD_META[name][0]
            if name == "regime":
                v.flag_values = np.array([0, 1, 2, 3], dtype=np.int8)
                v.flag_meanings = "exterior adhesion slip plastic"
            for k, xi in enumerate(XI_FIELDS):
                v[k] = sweep_fields(xi)[name]
        for name in ("Fx", "Fy", "Fn", "traction_coefficient"):
            v = ds.createVariable(name, "f8", (d,))
            v.units = "1" if name == "traction_coefficient" else "N"
            f = [sweep_fields(xi) for xi in XI_FIELDS]
            fx, fy, fn = (np.array([g[c].sum() * da for g in f]) for c in ("px", "py", "pn"))
            v[:] = {"Fx": fx, "Fy": fy, "Fn": fn, "traction_coefficient": fx / fn}[name]
        v = ds.createVariable("Mz", "f8", (d,))
        v.units = "N mm"
        v[:] = 0.0


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    out = argv[1]
    os.makedirs(out, exist_ok=True)
    write_run(os.path.join(out, "run3d.nc"))
    write_run(os.path.join(out, "run3d_hertz.nc"), hertz=True)
    write_sweep(os.path.join(out, "sweep3d.nc"),
                [("rolling.creepage", XI, "1"), ("rolling.lateral_creepage", ETA, "1")],
                lambda p, idx: None if idx == MISSING else
                creep_forces(p["rolling.creepage"], p["rolling.lateral_creepage"]))
    write_sweep(os.path.join(out, "sweep3d_spin.nc"),
                [("friction.mu", MUS, "1"), ("rolling.spin", SPIN, "1/mm")],
                lambda p, idx: creep_forces(0.0, 0.0, p["rolling.spin"], p["friction.mu"]))
    write_sweep_fields(os.path.join(out, "sweep3d_fields.nc"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
