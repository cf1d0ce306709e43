#!/usr/bin/python3
"""Per-revolution energy and u* of a twin-disc run (docs/case-file.md "twin_disc:").

  check_rig_energy.py ROLLSIM CASE WORKDIR [--set ...]
      Runs CASE (a twin-disc case whose output.fields hold ustar) and checks, per revolution k
      of disc 1 ([k T, (k+1) T], T = twin_disc_revolution_time):
      - revolution_dissipated_energy is the time integral of frictional_power + plastic_power:
        the file's value (a trapezoidal sum over every accepted time step) against the
        trapezoidal sum over the output records, I_h. (The protocol must not jump after t = 0:
        at a held step's start the power jumps, and the record there holds the state before
        the jump with the inputs after it, neither limit; ramps are fine.) Their difference is the quadrature error
        of I_h, which Richardson's estimate bounds: |I_h - I_2h| / 3 for a smooth integrand
        (I_2h from every other record); allowed: |I_h - I_2h| (3 times that), plus 1e-9 |I_h|
        for the records' rounding.
      - it is never negative (both powers dissipate: p . v_slip <= 0 by the friction law's
        direction, p . du_pl/dt >= 0 by the flow rule), nor is the power at any record;
      - revolution_ustar_exit_mean is the time mean of u* in the trailing cell (x lowest; the
        mean across y in 3D), checked against the records the same way; the largest value is
        at least the mean and at least the records' largest (the records are interpolated
        between steps: 1e-6 relative);
      - units: N mm/mm (2D) or N mm (3D), mm.
"""
import os
import subprocess
import sys

import netCDF4
import numpy as np

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def trapezoid(t, f, a, b):
    """Integral over [a, b] of the piecewise-linear interpolant through (t, f)."""
    inside = (t > a) & (t < b)
    tt = np.concatenate(([a], t[inside], [b]))
    ff = np.concatenate(([np.interp(a, t, f)], f[inside], [np.interp(b, t, f)]))
    return float(np.sum(0.5 * (ff[1:] + ff[:-1]) * np.diff(tt)))


def main():
    rollsim, case, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "rig.nc")
    subprocess.run([rollsim, "run", case, "-o", out, "--quiet", *sys.argv[4:]], check=True)
    with netCDF4.Dataset(out) as ds:
        three = getattr(ds, "dimension", 2) == 3
        T = float(ds.twin_disc_revolution_time)
        t = ds["time"][:].data
        power = ds["frictional_power"][:].data + ds["plastic_power"][:].data
        us = ds["ustar"][:].data
        trailing = us[:, :, 0].mean(axis=1) if three else us[:, 0]
        ends = ds["revolution_time_end"][:].data
        energy = ds["revolution_dissipated_energy"][:].data
        umean = ds["revolution_ustar_exit_mean"][:].data
        umax = ds["revolution_ustar_exit_max"][:].data
        units = (ds["revolution_dissipated_energy"].units, ds["revolution_ustar_exit_mean"].units,
                 ds["revolution_ustar_exit_max"].units)
    want = ("N mm" if three else "N mm/mm", "mm", "mm")
    check(f"units {units}", units == want, str(want))
    check(f"{len(energy)} revolutions, all written", len(energy) > 0 and np.all(np.isfinite(energy)))
    check("dissipated power >= 0 at every record", bool(np.all(power >= -1e-9 * np.abs(power).max())),
          f"min {power.min():.3g}")
    check("energy per revolution >= 0", bool(np.all(energy >= 0)), str(energy.min()))
    starts = np.concatenate(([0.0], ends[:-1]))
    worst_e = worst_u = 0.0
    for k, (a, b) in enumerate(zip(starts, ends)):
        ih = trapezoid(t, power, a, b)
        i2h = trapezoid(t[::2], power[::2], a, b)
        tol = abs(ih - i2h) + 1e-9 * abs(ih)
        worst_e = max(worst_e, abs(energy[k] - ih) / tol)
        check(f"revolution {k + 1}: energy {energy[k]:.6g} == integral of the power over the "
              f"records {ih:.6g} within {tol:.2g}", abs(energy[k] - ih) <= tol)
        uh = trapezoid(t, trailing, a, b) / (b - a)
        u2h = trapezoid(t[::2], trailing[::2], a, b) / (b - a)
        tol = abs(uh - u2h) + 1e-9 * abs(uh)
        worst_u = max(worst_u, abs(umean[k] - uh) / tol)
        check(f"revolution {k + 1}: mean exit u* {umean[k]:.6g} == records' {uh:.6g} within "
              f"{tol:.2g}", abs(umean[k] - uh) <= tol)
        rec = trailing[(t >= a) & (t <= b)]
        check(f"revolution {k + 1}: largest exit u* {umax[k]:.6g} >= its mean and the records' "
              f"largest {rec.max():.6g}",
              umax[k] >= umean[k] and umax[k] >= rec.max() * (1 - 1e-6))
    print(f"largest deviation / allowed: energy {worst_e:.3f}, u* {worst_u:.3f}")
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
