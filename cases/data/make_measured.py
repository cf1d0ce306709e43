#!/usr/bin/python3
"""Synthetic "measurements" for rollsim fit: the model at known parameters plus
deterministic noise, written as CSV with a header saying so.

    make_measured.py ROLLSIM CASE.yaml OUT.csv [--points N] [--sigma S] [--seed K]
                     [--lo LO] [--hi HI] [--twin-disc] [--set KEY=VALUE]...

The shipped data: make_measured.py build/rollsim cases/fit_creep_curve.yaml
cases/data/creep_curve_measured.csv and (--twin-disc) cases/fit_twin_disc.yaml
cases/data/twin_disc_measured.csv, with the defaults (sigma 0.002, seed 15).

Steady creep curve: runs `ROLLSIM sweep CASE --set sweep.rolling.creepage={linspace:
[LO, HI, N]}` (--lo/--hi, default 0 and -0.04) at the case's own parameter values (the
true values), adds
S * g_i to each traction coefficient, g_i = random.Random(K).gauss(0, 1) in order
(Python's Mersenne Twister: the same numbers on every platform and version), and
writes creepage,traction_coefficient.

Twin-disc protocol (--twin-disc): runs `ROLLSIM run CASE` and writes the per-step
traction coefficients (step_traction_coefficient of the file, steps 2..) as step,traction_coefficient.
"""
import argparse
import os
import random
import subprocess
import sys
import tempfile

import netCDF4


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rollsim")
    ap.add_argument("case")
    ap.add_argument("out")
    ap.add_argument("--points", type=int, default=41)
    ap.add_argument("--sigma", type=float, default=0.002)
    ap.add_argument("--seed", type=int, default=15)
    ap.add_argument("--lo", type=float, default=0.0)
    ap.add_argument("--hi", type=float, default=-0.04)
    ap.add_argument("--twin-disc", action="store_true")
    ap.add_argument("--set", action="append", default=[])
    a = ap.parse_args()
    sets = [x for s in a.set for x in ("--set", s)]
    with tempfile.TemporaryDirectory() as tmp:
        nc = os.path.join(tmp, "truth.nc")
        if a.twin_disc:
            cmd = [a.rollsim, "run", a.case, "-o", nc, "--quiet"] + sets
        else:
            lin = "{linspace: [%r, %r, %d]}" % (a.lo, a.hi, a.points)
            cmd = [a.rollsim, "sweep", a.case, "-o", nc, "--quiet",
                   "--set", "sweep.rolling.creepage=" + lin] + sets
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with netCDF4.Dataset(nc) as ds:
            if a.twin_disc:
                mu = [float(v) for v in ds["step_traction_coefficient"][:]]
                xs = list(range(1, len(mu) + 1))
                first = 1  # step 1 (the run-in at zero slip) is not a measurement
                xs, mu = xs[first:], mu[first:]
                head = "step,traction_coefficient"
            else:
                xs = [float(v) for v in ds["rolling_creepage"][:]]
                mu = [float(v) for v in ds["traction_coefficient"][:]]
                head = "creepage,traction_coefficient"
    rng = random.Random(a.seed)
    noisy = [m + a.sigma * rng.gauss(0.0, 1.0) for m in mu]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        f.write("# Synthetic measurements made by cases/data/make_measured.py (not a rig):\n")
        f.write("# %s at its own parameter values%s,\n" % (
            os.path.basename(a.case), " with --set " + " ".join(a.set) if a.set else ""))
        f.write("# plus noise sigma * g_i, sigma = %g, g_i = random.Random(%d).gauss(0, 1) "
                "in row order.\n" % (a.sigma, a.seed))
        f.write(head + "\n")
        for x, y in zip(xs, noisy):
            f.write("%.17g,%.17g\n" % (x, y))


if __name__ == "__main__":
    sys.exit(main())
