#!/usr/bin/env python3
"""mu(T) and tau_c0(T) in transients (docs/model.md §18 "Couplings", docs/verification.md 31).

  check_coupled_transient.py ROLLSIM HOT_CASE ERTZ_CASE OUT_DIR
  (HOT_CASE: cases/hot_creep_curve.yaml, ERTZ_CASE: cases/ertz_temperature.yaml)

1. Steady = transient limit, 2D: the case's contact at creepage -1 % (partial slip, T_max about
   85 degC, mu from 0.4 down to about 0.37), started from rest and rolled 1 ms (60 mm, 70 contact
   lengths: the heat of the start has left the contact many times over), against the steady
   coupled state of the same contact (an independent path: the steady solve with the
   Anderson-accelerated fixed point over the march, study/temperature.c). F_x to 1e-6 of mu F_n,
   T_max to 1e-6 of the rise: both are solved to their tolerances (rtol 1e-6, the fixed point's
   1e-9 of the rise), far inside that. The same with tau_c0(T) as well (plasticity tau_c0 300
   N/mm^2 falling to 150 at 400 degC: cells flow), and in 3D (Ertz & Knothe's contact in full
   sliding, 24 x 14 cells, mu 0.3 at 0 degC to 0.15 at 300 degC, rtol 1e-6, rolled 4 ms = 10
   contact lengths).
2. Energy per record of the coupled runs: heat into both bodies = 1e-3 (frictional +
   plastic_heat_fraction plastic power) to 1e-10 relative (the partition is exact per cell).
3. A constant table mu_T(T) = mu (0.4 at every temperature, friction.mu 0.4) is the run without a
   table bit for bit: every factor is 0.4/0.4 = 1 exactly, the bound times 1 is the bound, and
   no pass changes a factor, so each step is the uncoupled step: F_x, T_max and p_x of every
   record equal.
4. Cost of the coupling (temperature.coupling: newton, the default: Newton on the contact
   unknowns with the modes eliminated exactly in each evaluation): steps within 1.5 times the
   uncoupled run's; at rtol 1e-6 (where the passes of the alternation show) the Newton iterations
   per step within the uncoupled run's plus 1. The residual is the coupled one; its Jacobian is the
   contact's own until an iteration contracts poorly, so each iteration contracts the coupling's
   part of the error by at least the loop gain |dmu/dT| (T_max - T_bulk)/mu = 5.3e-4 65/0.4 = 0.09
   (a factor's change moves the heat and so the temperature by the same relative amount at most):
   one iteration more at most for the contact's Newton test (1/100 of IDA's tolerance; 0.09^2 <
   1/100) than the uncoupled solve, fewer on average. The alternation
   (temperature.coupling: fixed_point) costs a Newton iteration or two per pass after the first,
   each pass contracting the factors' change by that gain, two or three passes to the contact's
   Newton test: within the uncoupled run's plus 3 (it fails the bound of 1). The time steps follow
   the contact, whose history the coupling changes only by mu.
5. The two methods solve the same equations to the contact's Newton test (1/100 of IDA's
   tolerance): at rtol 1e-6 F_x of every record within rtol mu F_n of each other and T_max within
   rtol of the rise (the time integration's own error is of that order; the solves' differences
   are a hundredth of it).
"""
import os
import re
import subprocess
import sys

import netCDF4
import numpy as np

from temperature_checks import Checks, run

check = Checks()


def run_stats(rollsim, args, out):
    """The netCDF file and (steps, Newton iterations) of a run that must succeed."""
    cmd = [rollsim] + args + ["-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"IDA steps (\d+), Newton iterations (\d+)", r.stdout)
    if r.returncode != 0 or not m:
        print("FAIL", " ".join(cmd), r.stdout, r.stderr)
        sys.exit(1)
    return netCDF4.Dataset(out), int(m.group(1)), int(m.group(2))


def energy(d, frac=1.0):
    heat = np.asarray(d["heat_input_1"][1:], dtype=float) + np.asarray(d["heat_input_2"][1:], dtype=float)
    gen = 1e-3 * (np.asarray(d["frictional_power"][1:], dtype=float)
                  + frac * np.asarray(d["plastic_power"][1:], dtype=float))
    return float(np.max(np.abs(heat - gen) / np.abs(gen)))


def limit(name, steady, trans, mu_fn, rise):
    df = abs(float(trans["Fx"][-1]) - float(steady["Fx"][-1])) / mu_fn
    check(df <= 1e-6, f"{name}: transient F_x = steady coupled F_x "
          f"({float(steady['Fx'][-1]):.6g})", df, "<= 1e-6 mu F_n")
    dt = abs(float(trans["T_max"][-1]) - float(steady["T_max"][-1])) / rise
    check(dt <= 1e-6, f"{name}: transient T_max = steady T_max ({float(steady['T_max'][-1]):.2f} "
          "degC)", dt, "<= 1e-6 of the rise")
    e = energy(trans)
    check(e <= 1e-10, f"{name}: heat into both bodies = generated heat in every record", e,
          "<= 1e-10")


def main():
    rollsim, hot, ertz, out = sys.argv[1:5]
    os.makedirs(out, exist_ok=True)
    Fn = 1323.6
    pt = ["--set", "sweep=null", "--set", "rolling.creepage=-0.01"]
    tr = ["--set", "simulation.mode=transient", "--set", "simulation.initial_state=rest",
          "--set", "simulation.end_time=1e-3", "--set", "simulation.output_interval=1e-4"]

    # 1., 2. mu(T), 2D
    st = run(rollsim, ["run", hot] + pt, os.path.join(out, "steady.nc"))
    d, steps, iters = run_stats(rollsim, ["run", hot] + pt + tr, os.path.join(out, "transient.nc"))
    rise = float(st["T_max"][-1]) - 20.0
    check(rise > 50.0, "the contact heats (T_max - T_bulk > 50 K)", rise, "> 50")
    limit("mu(T) 2D", st, d, 0.4 * Fn, rise)

    # tau_c0(T) as well: cells flow
    tau = ["--set", "plasticity={tau_c0: 300, k_rel: 0.0}", "--set",
           "plasticity.tau_c0_table={temperature: [20, 400], tau_c0: [300, 150]}"]
    st2 = run(rollsim, ["run", hot] + pt + tau, os.path.join(out, "steady_tau.nc"))
    d2 = run(rollsim, ["run", hot] + pt + tau + tr, os.path.join(out, "transient_tau.nc"))
    check(int(d2["n_plastic"][-1]) > 0, "tau_c0(T): cells flow", int(d2["n_plastic"][-1]), "> 0")
    limit("mu(T) and tau_c0(T) 2D", st2, d2, 0.4 * Fn, float(st2["T_max"][-1]) - 20.0)

    # 3D
    e3 = ["--set", "grid.cells=[24,14]", "--set",
          "friction.temperature_table={temperature: [0, 300], mu: [0.3, 0.15]}"]
    s3 = run(rollsim, ["run", ertz] + e3, os.path.join(out, "steady3d.nc"))
    t3 = run(rollsim, ["run", ertz] + e3 + [
        "--set", "simulation.mode=transient", "--set", "simulation.initial_state=rest", "--set",
        "simulation.end_time=4e-3", "--set", "simulation.output_interval=1e-3", "--set",
        "solver.rtol=1e-6"], os.path.join(out, "transient3d.nc"))
    limit("mu(T) 3D", s3, t3, 0.3 * 100000.0, float(s3["T_max"][-1]))

    # 3. constant table = no table, bit for bit
    fields = ["--set", "output.fields=[px]"]
    const = ["--set", "friction.temperature_table={temperature: [20, 400], mu: [0.4, 0.4]}"]
    plain = ["--set", "friction.temperature_table=null"]
    a = run(rollsim, ["run", hot] + pt + tr + const + fields, os.path.join(out, "const.nc"))
    b, steps0, iters0 = run_stats(rollsim, ["run", hot] + pt + tr + plain + fields,
                                  os.path.join(out, "plain.nc"))
    same = all(np.array_equal(np.asarray(a[v][:]), np.asarray(b[v][:])) for v in ("Fx", "T_max", "px"))
    check(same, f"constant mu_T(T) = mu: F_x, T_max, p_x of all {len(a['time'])} records as "
          "without the table", same, True)

    # 4. cost: steps at the default tolerance; Newton iterations per step at rtol 1e-6, where the
    # alternation's passes show (5. uses the same runs)
    check(steps <= 1.5 * steps0, f"steps {steps} (uncoupled {steps0})", steps, f"<= {1.5 * steps0}")
    tight = ["--set", "solver.rtol=1e-6"]
    fp = ["--set", "temperature.coupling=fixed_point"]
    dn, steps_n, iters_n = run_stats(rollsim, ["run", hot] + pt + tr + tight,
                                     os.path.join(out, "newton_tight.nc"))
    df, steps_a, iters_a = run_stats(rollsim, ["run", hot] + pt + tr + tight + fp,
                                     os.path.join(out, "alternation_tight.nc"))
    _, steps_0, iters_0 = run_stats(rollsim, ["run", hot] + pt + tr + tight + plain,
                                    os.path.join(out, "plain_tight.nc"))
    per, per_a, per0 = iters_n / steps_n, iters_a / steps_a, iters_0 / steps_0
    check(per <= per0 + 1.0, f"rtol 1e-6: Newton iterations per step {per:.2f} (uncoupled "
          f"{per0:.2f})", per, f"<= {per0 + 1.0:.2f}")
    check(per_a <= per0 + 3.0, f"rtol 1e-6, alternation: Newton iterations per step {per_a:.2f}",
          per_a, f"<= {per0 + 3.0:.2f}")
    for name, st_ in (("newton", steps_n), ("alternation", steps_a)):
        check(st_ <= 1.5 * steps_0, f"rtol 1e-6, {name}: steps {st_} (uncoupled {steps_0})", st_,
              f"<= {1.5 * steps_0}")

    # 5. the two methods agree, at rtol 1e-6
    dfx = float(np.max(np.abs(np.asarray(dn["Fx"][:], dtype=float)
                              - np.asarray(df["Fx"][:], dtype=float)))) / (0.4 * Fn)
    check(dfx <= 1e-6, "newton and fixed_point transients: F_x of every record", dfx,
          "<= 1e-6 mu F_n")
    dtm = float(np.max(np.abs(np.asarray(dn["T_max"][:], dtype=float)
                              - np.asarray(df["T_max"][:], dtype=float)))) / rise
    check(dtm <= 1e-6, "newton and fixed_point transients: T_max of every record", dtm,
          "<= 1e-6 of the rise")
    if check.failures:
        sys.exit(1)


if __name__ == "__main__":
    main()
