#!/usr/bin/env python3
"""Surface temperature of CONTACT's example ertz_temperature (Ertz & Knothe's contact) by rollsim,
and the same heat source through two direct sums of the exact 1/sqrt(t) kernel:

  exact   piecewise-constant flux per cell, exact integral over each upstream cell and over the
          half cell up to the centre (what rollsim approximates with its sum of exponentials);
  CONTACT the same sums with the cell's own term 2 sqrt(dx/2) as CONTACT's m_temperature.f90
          writes it (twice the integral over the half cell in its normalisation).

  compare.py ROLLSIM OUT_DIR [CONTACT.out]

CONTACT's maximum temperatures are read from its output file when given (run.sh runs it when
CONTACT_ANCHOR is set), else they are the ones its published reference output prints.
"""
import math
import os
import re
import subprocess
import sys

import netCDF4
import numpy as np

CASES = [  # name, --set arguments (creepages, bulk temperatures)
    ("full sliding 1 m/s, bulk 0/0", ["rolling.creepage=-0.033333333", "temperature.bulk=[0, 0]"]),
    ("no sliding, bulk 0/150", ["rolling.creepage=0", "temperature.bulk=[0, 150]"]),
    ("full sliding 1 m/s, bulk 0/150", ["rolling.creepage=-0.033333333",
                                        "temperature.bulk=[0, 150]"]),
    # CONTACT rolls towards -x (chi = 180 deg); rollsim's frame is its mirror image in x, which
    # turns the sign of the spin (and of M_z)
    ("partial slip xi -2e-3, eta 1e-3, phi 2e-4, bulk 0/150",
     ["rolling.creepage=-0.002", "rolling.lateral_creepage=0.001", "rolling.spin=-0.0002",
      "temperature.bulk=[0, 150]"]),
]
PUBLISHED = [166.8, 75.00, 241.8, 90.85]  # examples/ertz_temperature.ref_out, MAX(T1,T2)


def contact_maxima(path):
    text = open(path).read()
    return [float(m) for m in re.findall(r"MAX\(T1,T2\)\s*\n\s*(?:\S+\s+){5}(\S+)", text)]


def direct_sums(path, beta, bulk):
    """T_max in the contact from the run's tractions and slip, by the two direct sums."""
    d = netCDF4.Dataset(path)
    x, V = d["x"][:], float(d["velocity"][-1])
    dx = float(x[1] - x[0])
    h = 0.5 * dx
    p = np.hypot(d["px"][-1], d["py"][-1])
    s = np.hypot(d["slip_x"][-1], d["slip_y"][-1]) * V
    pn = d["pn"][-1]
    q = 1e-3 * p * s  # W/mm^2
    q[pn <= 0] = 0.0
    eps = beta[0] / (beta[0] + beta[1])
    t_mean = bulk[0] + eps * (bulk[1] - bulk[0])
    fact = 1.0 / ((beta[0] + beta[1]) * math.sqrt(math.pi * V))  # both bodies: q (b_i/sum b)
    best = {"exact": -1e9, "CONTACT": -1e9}
    nx = len(x)
    for iy in range(q.shape[0]):
        row = q[iy]
        for ix in range(nx):
            if pn[iy, ix] <= 0:
                continue
            up = np.arange(ix + 1, nx)  # upstream: material enters at high x
            dist = x[up] - x[ix]
            tail = np.sum(row[up] * 2.0 * (np.sqrt(dist + h) - np.sqrt(dist - h)))
            own = row[ix] * 2.0 * math.sqrt(h)  # int_0^h ds/sqrt(s)
            best["exact"] = max(best["exact"], t_mean + fact * (tail + own))
            best["CONTACT"] = max(best["CONTACT"], t_mean + fact * (tail + 2.0 * own))
    return best, float(d["T_max"][-1]), d


def main():
    rollsim, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    ref = contact_maxima(sys.argv[3]) if len(sys.argv) > 3 else PUBLISHED
    source = "CONTACT run" if len(sys.argv) > 3 else "CONTACT (published ref_out)"
    here = os.path.dirname(os.path.abspath(__file__))
    case = os.path.join(here, "..", "..", "cases", "ertz_temperature.yaml")
    beta = [math.sqrt(50e-3 * 7.85e-6 * 450.0)] * 2
    print(f"| case | {source} T_max | rollsim T_max | diff | exact sums | CONTACT's sums on "
          "rollsim's source | F_x (N) | cells S/H |")
    print("|---|---|---|---|---|---|---|---|")
    for (name, sets), t_ref in zip(CASES, ref):
        path = os.path.join(out, re.sub(r"\W+", "_", name) + ".nc")
        cmd = [rollsim, "run", case, "-o", path, "--quiet"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        bulk = [float(v) for v in re.search(r"\[(.*)\]", sets[-1]).group(1).split(",")]
        sums, t_max, d = direct_sums(path, beta, bulk)
        print(f"| {name} | {t_ref:.2f} | {t_max:.2f} | {100 * (t_max / t_ref - 1):+.1f} % | "
              f"{sums['exact']:.2f} | {sums['CONTACT']:.2f} | {float(d['Fx'][-1]):.0f} | "
              f"{int(d['n_slip'][-1])}/{int(d['n_adhesion'][-1])} |")
    # the first case on three grids: rollsim's T_max converges with the cell size; CONTACT's
    # own-cell term adds q sqrt(dx/2)/((b1 + b2) sqrt(pi V)), which vanishes like sqrt(dx)
    print()
    print("| full sliding, bulk 0/0: cells (dx, dy mm) | rollsim T_max | exact sums | "
          "CONTACT's sums on rollsim's source |")
    print("|---|---|---|---|")
    for nx, ny in ((40, 23), (79, 45), (158, 90)):
        path = os.path.join(out, f"grid{nx}.nc")
        cmd = [rollsim, "run", case, "-o", path, "--quiet", "--set",
               f"grid.cells=[{nx}, {ny}]"] + sum((["--set", s] for s in CASES[0][1]), [])
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        sums, t_max, d = direct_sums(path, beta, [0.0, 0.0])
        print(f"| {nx} x {ny} ({15.8 / nx:.3g}, {22.5 / ny:.3g}) | {t_max:.2f} | "
              f"{sums['exact']:.2f} | {sums['CONTACT']:.2f} |")


if __name__ == "__main__":
    main()
