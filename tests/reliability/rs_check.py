"""Shared helpers of the reliability tests (tests/reliability/check_*.py): running rollsim
and checking that a netCDF file left by a run, complete or not, holds only complete records.

A record is complete when every quantity in it agrees with the others, each written by a
separate netCDF call: the time is k*output_interval, all values are finite, the regime
counts equal the counts of the regime field, F_x = sum(px)*dx, F_n is the same in every
record (constant normal load), the traction coefficient is F_x/F_n and |px| <= mu*pn.
Torn or missing data (zeros, fill values, garbage) break at least one of these.
"""
import os
import re
import shutil
import subprocess

import numpy as np

COUNTS = ("n_exterior", "n_adhesion", "n_slip", "n_plastic")

# The runs of cases/default.yaml pin what check_records relies on, so that edits of the
# default case cannot break these tests: output interval DT, friction coefficient MU, a
# constant normal load, the fields px, pn and regime, and the time tolerance 1e-6 under which
# the friction bound holds to the 1e-3 N/mm^2 that check_records asserts (and a 40 m run
# lasts long enough to be interrupted).
DT = 1.0e-5   # s
MU = 0.3
PIN = ["--set", f"simulation.output_interval={DT}", "--set", f"friction.mu={MU}",
       "--set", "contact.normal_load=178.9", "--set", "output.fields=[px, pn, slip, regime]",
       "--set", "solver.rtol=1e-6"]


def run(rollsim, args, cwd=None, timeout=120, env=None):
    """Run rollsim; returns (returncode, stdout, stderr) as text."""
    p = subprocess.run([rollsim] + list(args), cwd=cwd, capture_output=True, timeout=timeout,
                       env=env)
    return (p.returncode, p.stdout.decode("utf-8", "replace"),
            p.stderr.decode("utf-8", "replace"))


def summary_records(stdout):
    """The record count of the summary line 'output: FILE (N records)', or None."""
    m = re.search(r"output: .* \((\d+) records\)", stdout)
    return int(m.group(1)) if m else None


def check_records(ds, dt, mu, where, t_end=None):
    """Check every record of the open netCDF4.Dataset ds (see the module docstring);
    returns the number of records. t_end: the end time when the last record may be it."""
    ds.set_auto_mask(False)
    nrec = len(ds.dimensions["time"])
    if nrec == 0:
        return 0
    time = ds["time"][:]
    want = np.arange(nrec) * dt
    if t_end is not None and nrec > 1 and abs(time[-1] - t_end) <= 1e-12 * t_end:
        want[-1] = t_end
    assert np.allclose(time, want, rtol=1e-12, atol=1e-18), \
        f"{where}: times are not k*{dt}: {time[:5]} ... {time[-5:]}"
    x = ds["x"][:]
    nx = len(x)
    dx = x[1] - x[0]
    px, pn, regime = ds["px"][:], ds["pn"][:], ds["regime"][:]
    for name in ("px", "pn", "Fx", "Fn", "traction_coefficient", "creepage", "velocity",
                 "frictional_power", "plastic_power", "elastic_energy"):
        bad = ~np.isfinite(ds[name][:])
        assert not bad.any(), \
            f"{where}: {name} not finite in record(s) {np.nonzero(bad.reshape(nrec, -1).any(1))[0]}"
    total = np.zeros(nrec, dtype=np.int64)
    for k, name in enumerate(COUNTS):
        count = ds[name][:]
        total += count
        bad = count != (regime == k).sum(axis=1)
        assert not bad.any(), \
            f"{where}: {name} disagrees with regime in records {np.nonzero(bad)[0]}"
    assert (total == nx).all(), f"{where}: cell counts do not add up to {nx}: {total}"
    Fx, Fn = ds["Fx"][:], ds["Fn"][:]
    bad = np.abs(px.sum(axis=1) * dx - Fx) > 1e-9 * np.maximum(1.0, np.abs(Fx))
    assert not bad.any(), f"{where}: Fx != sum(px)*dx in records {np.nonzero(bad)[0]}"
    assert (Fn == Fn[0]).all() and Fn[0] > 0, f"{where}: Fn not constant: {Fn}"
    assert (pn == pn[0]).all(), f"{where}: pn differs between records"
    assert np.allclose(ds["traction_coefficient"][:], Fx / Fn, rtol=1e-12, atol=0), \
        f"{where}: traction_coefficient != Fx/Fn"
    excess = np.abs(px) - mu * pn
    assert excess.max() <= 1e-3, f"{where}: |px| exceeds mu*pn by {excess.max()}"
    return nrec


def prepare_dir(path):
    """An empty directory at path (whatever an earlier run left there removed)."""
    os.makedirs(path, exist_ok=True)
    for name in os.listdir(path):
        full = os.path.join(path, name)
        if os.path.ismount(full):
            subprocess.run(["umount", full], check=False)
        if os.path.isdir(full) and not os.path.islink(full):
            shutil.rmtree(full)
        else:
            os.remove(full)
    return path
