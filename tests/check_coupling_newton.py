#!/usr/bin/env python3
"""The Newton method of the coupled steady state with mu(T) and tau_c0(T) (docs/model.md §18
"Couplings", docs/verification.md 29-30).

  check_coupling_newton.py ROLLSIM CASE CASE3D OUT_DIR
      (CASE: cases/hot_creep_curve.yaml, CASE3D: cases/ertz_temperature.yaml)

1. Quadratic convergence on the case's mild table (mu 0.4 -> 0.2 over 20-400 degC), single runs
   from cold at creepage -0.4 %, -1 %, -4 %: at most 4 coupled solves (3 Newton steps). The
   first solve, at the cold surfaces' temperature, is off by the whole rise; Newton's error then
   squares at each step (1 -> 5e-3 -> 1e-7 -> 6e-14 of the rise at -4 %), so the third step is far
   below the tolerance 1e-9 of the rise. The fixed point (temperature.coupling: fixed_point),
   which converges linearly, needs 9 at -4 %: the bound fails for it.
2. Newton's coupled state equals the Anderson-accelerated fixed point's (an independent path to
   the same equations, temperature.coupling: fixed_point), along the case's 41-point curve with
   mu(T), with tau_c0(T) (tau_c0 300 -> 150 N/mm^2 over 20-400 degC, k_rel 0) and in 3D
   (CASE3D in full sliding with mu 0.3 -> 0.15 over 0-300 degC): F_x to 1e-8 of the largest
   |F_x| and the contact temperature to 1e-8 of the rise. Each stops when the contact
   temperature changes by at most 1e-9 of the rise, and the force moves by |dmu/dT| times that
   (1e-10 relative here), so two converged states agree to a few 1e-9; 1e-8 leaves a margin.
   The coupled solves of the curve: Newton's fewer than the fixed point's.
3. A steep table (mu 5 -> 0.01 over 20-200 degC; the fixed point fails at creepage -2 % and -4 %
   after 200 iterations): Newton converges from cold at both, and the state is a coupled one:
   every slipping cell at |p_x| = mu_T(T1) p_n to 1e-8 relative (the table interpolated here at
   the file's T1: mu moves by at most 1e-9 rise |dmu/dT| = 5e-9 relative at the tolerance).
"""
import os
import re
import subprocess
import sys

import netCDF4
import numpy as np

from temperature_checks import Checks

check = Checks()
SLIP = 2  # regime of a slipping cell in the files (docs/file-format.md)
STEEP = "friction.temperature_table={temperature: [20, 200], mu: [5, 0.01]}"
TAU = ["--set", "friction.temperature_table=null", "--set", "plasticity={tau_c0: 300, k_rel: 0.0}",
       "--set", "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [300, 150]}"]
MU3 = ["--set", "friction.temperature_table={temperature: [0, 300], mu: [0.3, 0.15]}"]
FIXED = ["--set", "temperature.coupling=fixed_point"]


def run(rollsim, args, out, expect_rc=0):
    """(the file, coupled solves, Newton steps) of `rollsim ARGS -o OUT`."""
    cmd = [rollsim] + args + ["-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != expect_rc:
        print("FAIL", " ".join(cmd), f"exit {r.returncode}", r.stdout, r.stderr)
        sys.exit(1)
    m = re.search(r"temperature coupling: (\d+) coupled solves, (\d+) Newton steps", r.stdout)
    if not m:
        print("FAIL: no coupling count in the output of", " ".join(cmd), r.stdout)
        sys.exit(1)
    return netCDF4.Dataset(out), int(m.group(1)), int(m.group(2))


def arr(d, v):
    return np.asarray(d[v][:], dtype=float)


def main():
    rollsim, case, case3, out = sys.argv[1:5]
    os.makedirs(out, exist_ok=True)
    single = ["run", case, "--set", "sweep=null", "--set", "output.error_estimate=false"]

    # 1. quadratic convergence
    for xi in (-0.004, -0.01, -0.04):
        _, solves, steps = run(rollsim, single + ["--set", f"rolling.creepage={xi}"],
                               os.path.join(out, "single.nc"))
        check(solves <= 4, f"mild table, creepage {xi} from cold: coupled solves ({steps} Newton "
              "steps)", solves, "<= 4")
    _, solves, _ = run(rollsim, single + ["--set", "rolling.creepage=-0.04"] + FIXED,
                       os.path.join(out, "single_fp.nc"))
    check(solves > 4, "the fixed point at creepage -4 % needs more (the bound is Newton's)", solves,
          "> 4")

    # 2. Newton = fixed point
    for name, cmd, extra in (("mu(T) curve", "sweep", []), ("tau_c0(T) curve", "sweep", TAU),
                             ("3D mu(T)", "run", MU3)):
        base = [cmd, case3 if name.startswith("3D") else case] + extra
        a, sa, _ = run(rollsim, base, os.path.join(out, "newton.nc"))
        b, sb, _ = run(rollsim, base + FIXED, os.path.join(out, "fixed_point.nc"))
        fa, fb, ta, tb = arr(a, "Fx"), arr(b, "Fx"), arr(a, "T_max"), arr(b, "T_max")
        bulk = 0.0 if name.startswith("3D") else 20.0
        df = float(np.max(np.abs(fa - fb)) / np.max(np.abs(fb)))
        dt = float(np.max(np.abs(ta - tb)) / np.max(tb - bulk))
        check(df <= 1e-8, f"{name}: Newton's F_x against the fixed point's", df, "<= 1e-8")
        check(dt <= 1e-8, f"{name}: Newton's T_max against the fixed point's, of the rise", dt,
              "<= 1e-8")
        check(sa < sb, f"{name}: coupled solves, Newton against the fixed point's {sb}", sa,
              f"< {sb}")

    # 3. steep table
    for xi in (-0.02, -0.04):
        d, solves, steps = run(rollsim, single + ["--set", f"rolling.creepage={xi}", "--set", STEEP,
                                                  "--set", "output.fields=[px, pn, regime]"],
                               os.path.join(out, "steep.nc"))
        px, pn, T1 = arr(d, "px")[-1], arr(d, "pn")[-1], arr(d, "T1")[-1]
        slip = (arr(d, "regime")[-1].astype(int) == SLIP) & (pn > 0)
        want = np.interp(T1, [20.0, 200.0], [5.0, 0.01]) * pn
        rel = float(np.max(np.abs(np.abs(px[slip]) - want[slip]) / want[slip]))
        check(slip.sum() > 10 and rel <= 1e-8, f"steep table, creepage {xi} from cold: converged "
              f"({solves} coupled solves, {steps} Newton steps), |p_x| = mu_T(T1) p_n in all "
              f"{int(slip.sum())} slipping cells", rel, "<= 1e-8")
    sys.exit(1 if check.failures else 0)


if __name__ == "__main__":
    main()
