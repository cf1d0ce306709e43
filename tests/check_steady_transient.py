"""Steady results against the transient from rest on the same grid (ctest, /usr/bin/python3).

    check_steady_transient.py ROLLSIM CASE.yaml OUTDIR DISTANCE [--start STATE.csv] [--set KEY=VALUE]...

The expectation of every steady number is an independent path through the code: the
transient from rest (docs/verification.md 3), run over DISTANCE mm of rolling at rtol 1e-8,
which must have settled (its traction coefficient moves by less than 1e-6 relative over
the last quarter of the run; the test fails otherwise rather than compare against an
unsettled value). For every point of the case's sweep: block,
  - `rollsim sweep` (continuation along the last key, warm starts across the others),
  - `rollsim run` in steady mode from rest (a single run),
must give the transient's F_x/F_n to 1e-4 relative (the issue's acceptance; both solver
errors are far smaller: Newton to 1e-10 of g, IDA to 1e-8), and neither the steady nor
the transient traction may point against the creepage (p_x xi <= 0 in every cell, to
1e-9 of max |p_x|), where the creepage has one sign.
With --start, a third steady run per point starts Newton from a stored (wrong) state:
STATE.csv (columns x, px, upl, ustar) is written as a restart file and given to
`rollsim run --restart`; it must end at the same steady state (or exit 3, which fails
this test as well: the transient path must be able to correct it).
"""
import itertools
import os
import subprocess
import sys

import netCDF4
import numpy as np

TOL = 1e-4
SETTLED = 1e-6


def fail(what):
    print("FAIL", what)
    sys.exit(1)


def run(rollsim, args):
    r = subprocess.run([rollsim] + args + ["--quiet"], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"rollsim {' '.join(args)} exited {r.returncode}: {r.stderr.strip()}")
    return r


def sets_args(sets):
    return [a for s in sets for a in ("--set", s)]


def last_record(path):
    ds = netCDF4.Dataset(path)
    tc = np.asarray(ds["traction_coefficient"][:], dtype=float)
    px = np.asarray(ds["px"][-1], dtype=float)
    xi = float(ds["creepage"][-1])
    ds.close()
    return tc, px, xi


def reversed_cells(px, xi):
    if xi == 0.0:
        return 0
    return int(np.sum(px * xi > 1e-9 * np.max(np.abs(px))))


def restart_file(csv, path):
    """A restart file (one record: time, x, px, upl, ustar) from a stored state."""
    with open(csv) as f:
        lines = [line.strip() for line in f if line.strip() and not line.startswith("#")]
    names = lines[0].split(",")
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    data = {name: rows[:, k] for k, name in enumerate(names)}
    ds = netCDF4.Dataset(path, "w")
    ds.createDimension("time", None)
    ds.createDimension("x", rows.shape[0])
    ds.createVariable("time", "f8", ("time",))[0] = 0.0
    ds.createVariable("x", "f8", ("x",))[:] = data["x"]
    for name in ("px", "upl", "ustar"):
        ds.createVariable(name, "f8", ("time", "x"))[0, :] = data[name]
    ds.close()


def main():
    rollsim, case, outdir, distance = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    opts = {sys.argv[i]: sys.argv[i + 1] for i in range(5, len(sys.argv) - 1, 2)}
    sets = [sys.argv[i + 1] for i in range(5, len(sys.argv) - 1, 2) if sys.argv[i] == "--set"]
    os.makedirs(outdir, exist_ok=True)
    start = None
    if "--start" in opts:
        start = os.path.join(outdir, "start.nc")
        restart_file(opts["--start"], start)
    sweep_nc = os.path.join(outdir, "sweep.nc")
    run(rollsim, ["sweep", case, "-o", sweep_nc] + sets_args(sets))
    ds = netCDF4.Dataset(sweep_nc)
    dims = list(ds["traction_coefficient"].dimensions)  # the swept keys (profiles add x)
    keys = [ds[d].getncattr("key") for d in dims]
    values = [np.asarray(ds[d][:], dtype=float) for d in dims]
    tc_sweep = np.asarray(ds["traction_coefficient"][:], dtype=float)
    velocity = float(np.asarray(ds["velocity"][:]).flat[0])
    ds.close()
    interval = f"simulation.output_interval={distance / 40 / velocity:.6g}"
    worst = 0.0
    for idx in itertools.product(*[range(len(v)) for v in values]):
        point = [f"{keys[a]}={values[a][i]:.17g}" for a, i in enumerate(idx)]
        label = " ".join(f"{keys[a]}={values[a][i]:g}" for a, i in enumerate(idx))
        single_nc = os.path.join(outdir, "single.nc")
        trans_nc = os.path.join(outdir, "transient.nc")
        run(rollsim, ["run", case, "-o", single_nc, "--set", "simulation.mode=steady"]
            + sets_args(sets + point))
        run(rollsim, ["run", case, "-o", trans_nc, "--set", "simulation.mode=transient",
                      "--set", "simulation.initial_state=rest",
                      "--set", f"simulation.rolled_distance={distance}",
                      "--set", "solver.rtol=1e-8", "--set", "output.fields=[px]"]
            + sets_args(sets + point + [interval]))
        tc_single, px_single, xi = last_record(single_nc)
        tc_t, px_t, _ = last_record(trans_nc)
        ref = tc_t[-1]
        quarter = tc_t[3 * len(tc_t) // 4]
        scale = max(abs(ref), 1e-12)
        if abs(ref - quarter) > SETTLED * scale:
            fail(f"{label}: the transient has not settled over {distance} mm "
                 f"(F_x/F_n {quarter:.8f} -> {ref:.8f})")
        e_single = abs(tc_single[-1] - ref) / scale
        e_sweep = abs(tc_sweep[idx] - ref) / scale
        rev = reversed_cells(px_single, xi), reversed_cells(px_t, xi)
        worst = max(worst, e_single, e_sweep)
        ok = e_single <= TOL and e_sweep <= TOL and rev == (0, 0)
        detail = ""
        if start:
            started_nc = os.path.join(outdir, "started.nc")
            run(rollsim, ["run", case, "-o", started_nc, "--set", "simulation.mode=steady",
                          "--restart", start] + sets_args(sets + point))
            tc_started, px_started, _ = last_record(started_nc)
            e_started = abs(tc_started[-1] - ref) / scale
            worst = max(worst, e_started)
            ok = ok and e_started <= TOL and reversed_cells(px_started, xi) == 0
            detail = f" from the stored state {tc_started[-1]:.6f} ({e_started:.1e})"
        print(f"{'ok  ' if ok else 'FAIL'} {label}: transient {ref:.6f} single {tc_single[-1]:.6f} "
              f"({e_single:.1e}) sweep {tc_sweep[idx]:.6f} ({e_sweep:.1e}){detail} "
              f"reversed cells steady/transient {rev[0]}/{rev[1]}")
        if not ok:
            sys.exit(1)
    print(f"largest relative difference {worst:.2e} (tolerance {TOL:g})")


if __name__ == "__main__":
    main()
