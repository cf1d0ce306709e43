#!/usr/bin/env python3
"""Issue 44 item 3: the forces extrapolated to zero cell size (docs/model.md §19).

Carter's 2D case (cases/carter2d.yaml, xi = -2.4e-4; closed form F_x/(mu F_n) = 0.64,
docs/verification.md §2) with grid.align_edges (the contact edges +-a on cell faces, so that
the first-order error is C h with one C on all three grids):
  - 200 cells: the estimate is reliable, and traction_coefficient_extrapolated / mu lies within
    a tenth of the plain result's error of 0.64 (Richardson from first to second order: the
    remaining error is O(h^2), h = a/96 here);
  - 400 cells: the same within a tenth again of the 200-cell extrapolated error bound
    (the extrapolated values converge faster than first order);
  - without grid.align_edges (the default extent 1.05: a/dx = 47.6) at 100 cells the estimate
    is unreliable and the extrapolated variable holds its fill value (no value is claimed);
  - a sweep over three creepages writes per point the same extrapolated values as single runs
    (the sweep's path through its point messages against the run's), to 1e-6 relative.
Usage: check_extrapolation.py ROLLSIM CASE WORKDIR
"""
import os
import subprocess
import sys

import netCDF4
import numpy as np

from solver_checks import Checks

check = Checks()
MU, CARTER = 0.3, 0.64


def run(binary, case, out, sets, cmd="run"):
    args = [binary, cmd, case, "-o", out, "--quiet"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        print(p.stdout, p.stderr)
        return None
    return netCDF4.Dataset(out)


def main():
    binary, case, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    errs = {}
    for n in (200, 400):
        d = run(binary, case, os.path.join(work, f"aligned{n}.nc"),
                ["grid.align_edges=true", f"grid.cells={n}"])
        if d is None:
            check(f"{n} cells aligned: the run completed", False)
            return 1
        plain = float(d["traction_coefficient"][0]) / MU
        ext = float(np.ma.filled(d["traction_coefficient_extrapolated"][:], np.nan)[0]) / MU
        rel = int(d["error_reliable"][0])
        errs[n] = (abs(plain - CARTER), abs(ext - CARTER))
        check(f"{n} cells aligned: the estimate is reliable", rel == 1, f"error_reliable {rel}")
        check(f"{n} cells aligned: extrapolated within a tenth of the plain error of 0.64",
              abs(ext - CARTER) <= 0.1 * abs(plain - CARTER),
              f"plain {plain:.6f}, extrapolated {ext:.6f}")
    check("400 cells: the extrapolated error below a tenth of the plain 200-cell one's",
          errs[400][1] <= 0.1 * errs[200][0], f"{errs[400][1]:.3g} vs {errs[200][0]:.3g}")
    d = run(binary, case, os.path.join(work, "unaligned.nc"), [])
    if d is None:
        check("unaligned: the run completed", False)
        return 1
    ext = np.ma.filled(d["traction_coefficient_extrapolated"][:], np.nan)[0]
    check("100 cells on +-1.05 a: unreliable, no extrapolated value",
          int(d["error_reliable"][0]) == 0 and np.isnan(ext), f"{d['error_reliable'][0]}, {ext}")
    creep = [-1.2e-4, -2.4e-4, -4.8e-4]
    sets = ["grid.align_edges=true", "grid.cells=200"]
    s = run(binary, case, os.path.join(work, "sweep.nc"),
            sets + [f"sweep.rolling.creepage=[{', '.join(map(str, creep))}]"], cmd="sweep")
    if s is None:
        check("sweep: completed", False)
        return 1
    fs = np.ma.filled(s["Fx_extrapolated"][:], np.nan)
    for k, xi in enumerate(creep):
        d = run(binary, case, os.path.join(work, f"single{k}.nc"),
                sets + [f"rolling.creepage={xi}"])
        f1 = float(np.ma.filled(d["Fx_extrapolated"][:], np.nan)[0]) if d else np.nan
        check(f"sweep point xi = {xi}: Fx_extrapolated as the single run's",
              np.isfinite(f1) and abs(fs[k] - f1) <= 1e-6 * abs(f1), f"{fs[k]!r} vs {f1!r}")
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
