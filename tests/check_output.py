#!/usr/bin/python3
"""Check a file written by tests/test_output_crash_writer.c with netCDF4 (the reader
post-processing uses): format, dimensions, units, CF attributes and every value.

Usage: check_output.py FILE RECORDS
"""
import math
import sys

import netCDF4
import numpy as np

FIELDS = ["px", "pn", "slip", "upl", "ustar", "tauc"]

CASE_TEXT = "title: crash test\n" + "".join(
    f"# line {k:03d} of a long case text, so the header spans blocks\n" for k in range(100))

UNITS = {  # docs/file-format.md "Run files", 2D
    "time": "s", "x": "mm", "Fx": "N/mm", "Fn": "N/mm", "traction_coefficient": "1",
    "creepage": "1", "velocity": "mm/s", "n_exterior": "1", "n_adhesion": "1",
    "n_slip": "1", "n_plastic": "1", "frictional_power": "N mm/s/mm",
    "plastic_power": "N mm/s/mm", "elastic_energy": "N mm/mm", "px": "N/mm2", "pn": "N/mm2",
    "slip": "1", "upl": "mm", "ustar": "mm", "tauc": "N/mm2", "regime": "1",
}


def check_values(ds, nrec, path):
    """Records 0..nrec-1 hold the values the writer computes (see its header)."""
    nx = len(ds.dimensions["x"])
    rec = np.arange(nrec, dtype=np.float64)
    i = np.arange(nx, dtype=np.float64)
    for f, name in enumerate(FIELDS):
        expected = 1e4 * rec[:, None] + 1e3 * f + i[None, :]
        got = np.ma.getdata(ds.variables[name][:nrec, :])
        assert np.array_equal(got, expected), f"{path}: {name} differs"
    regime = (np.arange(nrec)[:, None] + np.arange(nx)[None, :]) % 4
    got = np.ma.getdata(ds.variables["regime"][:nrec, :])
    assert np.array_equal(got, regime), f"{path}: regime differs"
    scalars = {
        "time": 1e-3 * rec,
        "Fx": rec + 0.5,
        "Fn": 2.0 * rec + 1.0,
        "traction_coefficient": (rec + 0.5) / (2.0 * rec + 1.0),
        "creepage": -1e-6 * rec,
        "velocity": 1000.0 + rec,
        "n_exterior": np.arange(nrec) % 7,
        "n_adhesion": np.arange(nrec) % 11,
        "n_slip": np.arange(nrec) % 13,
        "n_plastic": np.arange(nrec) % 17,
        "frictional_power": rec / 4.0,
        "plastic_power": rec / 8.0,
        "elastic_energy": rec / 16.0,
    }
    for name, expected in scalars.items():
        got = np.ma.getdata(ds.variables[name][:nrec])
        assert np.array_equal(got, expected), f"{path}: {name} differs"
    x = np.ma.getdata(ds.variables["x"][:])
    assert np.array_equal(x, i), f"{path}: x differs"


def check_file(path, nrec):
    with netCDF4.Dataset(path) as ds:
        assert ds.data_model == "NETCDF3_64BIT_OFFSET", ds.data_model
        # dimensions
        assert set(ds.dimensions) == {"time", "x"}, list(ds.dimensions)
        assert ds.dimensions["time"].isunlimited()
        assert len(ds.dimensions["time"]) == nrec, len(ds.dimensions["time"])
        nx = len(ds.dimensions["x"])
        # global attributes
        assert ds.Conventions == "CF-1.10"
        assert ds.title == "crash test"
        assert ds.source.startswith("rollsim "), ds.source
        assert ds.history == "test_output_crash_writer"
        assert ds.case == CASE_TEXT, ds.case[:100]
        assert ds.status == "complete", repr(ds.status)
        # variables: all of docs/file-format.md, each with units and long_name
        assert set(ds.variables) == set(UNITS), sorted(ds.variables)
        for name, var in ds.variables.items():
            assert var.units == UNITS[name], f"{name}: units {var.units!r}"
            assert var.long_name, f"{name}: no long_name"
            expected_dims = (("time", "x") if name in FIELDS + ["regime"]
                             else ("x",) if name == "x" else ("time",))
            assert var.dimensions == expected_dims, f"{name}: {var.dimensions}"
        assert ds["time"].standard_name == "time" and ds["time"].axis == "T"
        assert ds["x"].axis == "X"
        for name in ("n_exterior", "n_adhesion", "n_slip", "n_plastic"):
            assert ds[name].dtype == np.int32, f"{name}: {ds[name].dtype}"
        regime = ds["regime"]
        assert regime.dtype == np.int8, regime.dtype
        assert regime.flag_values.dtype == np.int8
        assert list(regime.flag_values) == [0, 1, 2, 3]
        assert regime.flag_meanings == "exterior adhesion slip plastic"
        # values
        check_values(ds, nrec, path)
        assert all(math.isfinite(v) for v in ds["traction_coefficient"][:])
    print(f"{path}: {nrec} records x {nx} cells, all checks passed")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    check_file(sys.argv[1], int(sys.argv[2]))
