#!/usr/bin/env python3
"""Twin-disc rig mode (issue 4 item 4, docs/model.md §8): three runs of
tests/cases/twin_disc_small.yaml (constant slip 0.5 %, k_rel = 0.2 > 0):

 1. recovery 1: the plastic state comes back every revolution, the yield limit keeps
    growing, so the traction coefficient per revolution must be non-decreasing and
    converging (increments shrink; the last is below a fifth of the first), and it
    stays below the plain-rolling value (the bound min(g, tau_c) <= g);
 2. tau_c0 = 1e4 N/mm^2, above every mu p_n (mu p0 = 735): no plasticity, so the
    twin-disc run is plain rolling: F_x(t) must equal that of a plain case built
    here from the disc data (q = F/b, R, V, xi = -slip; an independent check of
    the mapping too);
 3. recovery 0: the material entering is fresh every revolution: F_x(t) must equal
    the plain rolling case with the same plasticity (fresh inflow).
Comparisons 2 and 3 are between two different integrations (the rig mode steps one
IDA step at a time with a bounded step): at rtol = atol = 1e-8 each has a global
error ~1e-7 of max|F_x|, so they must agree to 1e-5 of max|F_x|; a wrong load,
radius, speed, slip sign or a leaking memory changes F_x by percents.

usage: check_twin_disc.py ROLLSIM TWIN_CASE PLAIN_CASE WORKDIR
"""
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np

TIGHT = ["--set", "solver.rtol=1e-8", "--set", "solver.atol=1e-8"]


def run(rollsim, case, out, sets):
    cmd = [rollsim, "run", case, "-o", out, "--quiet"] + sets
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return netCDF4.Dataset(out)


def same_fx(a, b, label, failure, fails):
    """F_x(t) of runs a and b agree to 1e-5 of max|F_x| (see above); False if the
    record counts differ."""
    fa, fb = a["Fx"][:].data, b["Fx"][:].data
    if fa.shape != fb.shape:
        fails.append(f"record counts differ: {fa.shape} vs {fb.shape}")
        return False
    dev = np.abs(fa - fb).max() / np.abs(fb).max()
    print(f"{label}: max |dF_x| / max|F_x| = {dev:.2e}")
    if dev > 1e-5:
        fails.append(f"{failure} by {dev:.2e}")
    return True


def main():
    rollsim, twin, plain, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    fails = []

    # Disc data of the test case (as in the file) -> plain rolling inputs.
    R1 = R2 = 23.5
    width, force, rpm, slip, revs = 10.0, 7300.0, 400.0, 0.005, 12
    V = 2 * math.pi * rpm / 60 * R1
    T = 2 * math.pi * R1 / V
    plain_sets = ["--set", f"contact.normal_load={force / width!r}",
                  "--set", f"contact.radius={1 / (1 / R1 + 1 / R2)!r}",
                  "--set", f"rolling.velocity={V!r}",
                  "--set", f"rolling.creepage={-slip!r}",
                  "--set", f"simulation.end_time={revs * T!r}",
                  "--set", f"simulation.output_interval={T / 20!r}"]

    # 1. recovery 1
    d = run(rollsim, twin, os.path.join(work, "recovery1.nc"), [])
    mu_rev = d["revolution_traction_coefficient"][:].data
    print("traction coefficient per revolution:", " ".join(f"{m:.5f}" for m in mu_rev))
    inc = np.diff(mu_rev)
    tol = 1e-5 * abs(mu_rev).max()  # rtol 1e-6 noise of a per-revolution mean, with margin
    if np.any(inc < -tol):
        fails.append(f"traction coefficient decreases between revolutions: {inc}")
    if np.any(inc[1:] > inc[:-1] + tol):
        fails.append(f"increments do not shrink (not converging): {inc}")
    if not inc[-1] < 0.2 * inc[0]:
        fails.append(f"last increment {inc[-1]:.3g} not below a fifth of the first {inc[0]:.3g}")
    step_mu = d["step_traction_coefficient"][:].data
    w0 = d["step_window_start"][0]
    t = d["time"][:].data
    mu_t = d["traction_coefficient"][:].data
    sel = t >= w0 - 1e-12
    print(f"step traction coefficient {step_mu[0]:.6f} (records in its window: mean "
          f"{mu_t[sel].mean():.6f})")
    # the step mean (time integral over IDA steps) and the mean of the records
    # (every T/20) agree to the variation of mu over a record interval
    if abs(step_mu[0] - mu_t[sel].mean()) > 0.01 * step_mu[0]:
        fails.append("step traction coefficient disagrees with the records in its window")

    # 2. tau_c0 above every mu p_n: plain rolling (elastic case).
    hi = ["--set", "plasticity.tau_c0=1e4"]
    a = run(rollsim, twin, os.path.join(work, "tauc_high.nc"), hi + TIGHT)
    b = run(rollsim, plain, os.path.join(work, "plain_elastic.nc"),
            plain_sets + ["--set", "plasticity=null"] + TIGHT)
    for name, ds in (("twin disc", a), ("plain", b)):
        print(f"{name}: {len(ds['time'])} records, final F_x = {ds['Fx'][-1]:.6f} N/mm")
    if same_fx(a, b, "tau_c0 high vs plain elastic rolling",
               "tau_c0 high differs from plain rolling", fails):
        plain_elastic_mu = b["traction_coefficient"][-1]
        if mu_rev.max() > plain_elastic_mu * (1 + 1e-6):
            fails.append(f"plastic traction {mu_rev.max():.6f} above the plain rolling "
                         f"value {plain_elastic_mu:.6f}")

    # 3. recovery 0: fresh material every revolution = plain rolling with plasticity.
    a = run(rollsim, twin, os.path.join(work, "recovery0.nc"),
            ["--set", "twin_disc.recovery=0"] + TIGHT)
    b = run(rollsim, plain, os.path.join(work, "plain_plastic.nc"), plain_sets + TIGHT)
    if same_fx(a, b, "recovery 0 vs plain plastic rolling",
               "recovery 0 differs from rolling with fresh material", fails):
        mu0 = a["revolution_traction_coefficient"][:].data
        print("recovery 0, per revolution:", " ".join(f"{m:.5f}" for m in mu0))
    for f in fails:
        print("FAIL:", f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
