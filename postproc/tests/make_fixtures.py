#!/usr/bin/python3
"""Synthetic netCDF files for the post-processing tests (no rollsim needed).

Usage: make_fixtures.py OUTDIR

  sweep_krel_creep.nc   a sweep file as docs/file-format.md describes it ("one dimension per swept key,
                        coordinate variables holding the values, scalar results over those
                        dimensions"): dimensions plasticity_k_rel (4) x rolling_creepage (5), the
                        coordinates carrying the dotted key in the attribute `key`; creepage stored
                        in descending order, one point missing (fill value) = a failed sweep point.
  sweep_creep_tau.nc    the same result laid out the other way round: rolling_creepage (4) x
                        plasticity_tau_c0 (2), to check the reader does not assume an axis order.
  no_records.nc         a run file whose run failed before the first record (time has length 0).

The results follow traction(), which check_postproc.py uses as the expected value.
"""
import os
import sys

import netCDF4
import numpy as np

K_REL = [0.95, 0.6, 0.0, -0.3]
CREEPAGE = list(np.linspace(0.0, -0.01, 5))  # descending, as a sweep block would list it
MISSING = (2, 3)  # (k_rel index, creepage index) of the failed point in sweep_krel_creep.nc

CREEPAGE_B = [-0.004, -0.001, -0.002, -0.008]  # unordered on purpose
TAU_C0 = [200.0, 350.0]


def traction(creepage, k_rel=0.0, tau_c0=200.0):
    """A made-up smooth creep curve: saturates at 0.5 (0.8 + 0.2 k_rel) (tau_c0 / 350)^0.1."""
    return -0.5 * np.tanh(creepage / 0.002) * (0.8 + 0.2 * k_rel) * (tau_c0 / 350.0) ** 0.1


def _globals(ds, title, case):
    ds.Conventions = "CF-1.10"
    ds.title = title
    ds.source = "rollsim_post test fixture"
    ds.history = "make_fixtures.py"
    ds.case = case
    ds.status = "complete"


def _coordinate(ds, key, values, units, long_name):
    name = key.replace(".", "_")
    ds.createDimension(name, len(values))
    v = ds.createVariable(name, "f8", (name,))
    v[:] = values
    v.units = units
    v.long_name = long_name
    v.key = key
    return name


def _result(ds, dims, values, fill=None):
    v = ds.createVariable("traction_coefficient", "f8", dims, fill_value=fill)
    v.units = "1"
    v.long_name = "traction coefficient Fx/Fn"
    v[...] = values
    fn = ds.createVariable("Fn", "f8", dims)
    fn.units = "N/mm"
    fn.long_name = "total normal force on body 1"
    fn[...] = np.full(np.shape(values), 1323.6)
    return v


def write_sweep_a(path):
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, "synthetic sweep k_rel x creepage",
                 "title: synthetic\nfriction:\n  mu: 0.5\nsweep:\n  plasticity.k_rel: "
                 "[0.95, 0.6, 0.0, -0.3]\n  rolling.creepage: {linspace: [0.0, -0.01, 5]}\n")
        dk = _coordinate(ds, "plasticity.k_rel", K_REL, "1", "k_tau/(G + k_tau)")
        dc = _coordinate(ds, "rolling.creepage", CREEPAGE, "1", "creepage")
        values = np.array([[traction(c, k) for c in CREEPAGE] for k in K_REL])
        values = np.ma.masked_array(values, mask=np.zeros_like(values, dtype=bool))
        values[MISSING] = np.ma.masked
        _result(ds, (dk, dc), values, fill=-9999.0)


def write_sweep_b(path):
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, "synthetic sweep creepage x tau_c0", "title: synthetic\n")
        dc = _coordinate(ds, "rolling.creepage", CREEPAGE_B, "1", "creepage")
        dt = _coordinate(ds, "plasticity.tau_c0", TAU_C0, "N/mm2", "initial yield limit")
        values = np.array([[traction(c, 0.0, t) for t in TAU_C0] for c in CREEPAGE_B])
        _result(ds, (dc, dt), values)


def write_no_records(path):
    with netCDF4.Dataset(path, "w") as ds:
        _globals(ds, "failed run", "title: failed run\nfriction:\n  mu: 0.3\n")
        ds.status = "failed: steady solver did not converge at t = 0 s"
        ds.createDimension("time", None)
        ds.createDimension("x", 10)
        t = ds.createVariable("time", "f8", ("time",))
        t.units = "s"
        x = ds.createVariable("x", "f8", ("x",))
        x.units = "mm"
        x[:] = np.linspace(-1.0, 1.0, 10)
        for name in ("px", "pn"):
            v = ds.createVariable(name, "f8", ("time", "x"))
            v.units = "N/mm2"
        for name in ("Fx", "Fn", "traction_coefficient", "creepage", "velocity"):
            ds.createVariable(name, "f8", ("time",))


def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    write_sweep_a(os.path.join(outdir, "sweep_krel_creep.nc"))
    write_sweep_b(os.path.join(outdir, "sweep_creep_tau.nc"))
    write_no_records(os.path.join(outdir, "no_records.nc"))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
