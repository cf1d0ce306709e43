#!/usr/bin/env python3
"""Issue 47: what the main job's 2D start-up costs at the default tolerance, in counts (never
in time), and what the tolerance costs in accuracy.

cases/default.yaml (Carter, 100 cells over +-1.05 a, 40 mm rolled from rest), solver.rtol left
auto. Checked:
  - the tolerance run is the rule's (docs/case-file.md: 0.06 dx/a within [1e-6, 3e-3]; here
    dx = 2.1 a / 100, so 1.26e-3), in the summary and in the file's attribute solver_rtol;
  - IDA steps per cell passage at most 0.5: half of a fixed-shift scheme's one per passage
    (rtol 1e-6 takes 0.83: the traction evolves on the contact length, 100 cells);
  - Jacobian evaluations per IDA step below 1: the modified Newton keeps a factorisation while
    no cell changes branch (exact Newton evaluates one per iteration, 2-3 per step here);
  - the integration's error below the grid's: the final F_x/(mu F_n) within a tenth of the
    grid's own error (steady on this grid minus Carter's 0.64) of the steady solution on the
    same grid, solved by the steady solver (rollsim's other path to the same state).
Usage: check_transient_counts_2d.py ROLLSIM CASE WORKDIR
"""
import os
import sys

import netCDF4

from solver_checks import Checks, run_counts

check = Checks()
CARTER = 0.64  # Carter's closed form for this case's creepage (docs/verification.md §2)
KEYS = ("rtol", "steps", "jacobians", "per_passage", "mu")


def main():
    binary, case, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "default.nc")
    c = run_counts(binary, case, out, ["--quiet"], KEYS)
    check("the run completed and printed its counts", c is not None and
          all(c[k] is not None for k in KEYS),
          f"{c}")
    s = run_counts(binary, case, os.path.join(work, "steady.nc"),
                   ["--quiet", "--set", "simulation.mode=steady", "--set",
                    "output.error_estimate=false"], ("mu",))
    if c is None or None in [c[k] for k in ("rtol", "steps", "jacobians", "per_passage")] \
            or s is None or s["mu"] is None:
        return 1
    want = 0.06 * 2.1 / 100
    with netCDF4.Dataset(out) as d:
        attr = float(d.getncattr("solver_rtol"))
    check(f"solver.rtol auto = {want:g} (summary and file)",
          abs(c["rtol"] - want) <= 1e-9 and abs(attr - want) <= 1e-15 * want + 1e-18,
          f"{c['rtol']}, {attr!r}")
    check("IDA steps per cell passage at most 0.5", c["per_passage"] <= 0.5,
          f"{c['per_passage']}")
    per_step = c["jacobians"] / c["steps"]
    check("Jacobian evaluations per IDA step below 1", per_step < 1.0,
          f"{c['jacobians']:.0f} / {c['steps']:.0f} = {per_step:.3f}")
    grid_error = s["mu"] - CARTER
    dev = abs(c["mu"] - s["mu"])
    check("final F_x/(mu F_n) within a tenth of the grid's error of the steady solution",
          grid_error > 0 and dev <= 0.1 * grid_error,
          f"|{c['mu']} - {s['mu']}| = {dev:.3g}, grid's error {grid_error:.3g}")
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
