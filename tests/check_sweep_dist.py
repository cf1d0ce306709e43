#!/usr/bin/python3
"""Distributed sweeps (issue 16): a file from `mpirun -n N rollsim sweep` or from `rollsim
merge` of `--part K/N` files must hold the serial sweep's numbers bit for bit, because each
continuation line is computed whole by the same code from the same inputs (lines start from
rest; nothing carries over between them).

  check_sweep_dist.py same SERIAL.nc OTHER.nc [--ranks N]
      Every variable of SERIAL is in OTHER with identical bits (NaN where NaN), the case, title
      and status attributes are equal; with --ranks N: OTHER has the variable rank (each point's
      rank in 0..N-1, every rank computed points) and the attribute ranks = N.
"""
import sys

import netCDF4
import numpy as np

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def same(serial, other, ranks):
    with netCDF4.Dataset(serial) as a, netCDF4.Dataset(other) as b:
        a.set_auto_mask(False)
        b.set_auto_mask(False)
        for name, va in a.variables.items():
            if name not in b.variables:
                check(f"{name} in {other}", False)
                continue
            x, y = va[:], b.variables[name][:]
            if x.dtype.kind == "f":
                eq = x.shape == y.shape and np.array_equal(x.view(np.uint64 if x.itemsize == 8 else np.uint32),
                                                          y.view(np.uint64 if y.itemsize == 8 else np.uint32))
            else:
                eq = x.shape == y.shape and np.array_equal(x, y)
            check(f"{name}: bitwise equal", eq)
        for att in ("case", "title", "status"):
            check(f"attribute {att} equal", a.getncattr(att) == b.getncattr(att),
                  f"{a.getncattr(att)!r} vs {b.getncattr(att)!r}" if att == "status" else "")
        if ranks:
            check("attribute ranks", int(b.ranks) == ranks, str(b.getncattr("ranks")))
            r = b.variables["rank"][:]
            check("every point has a rank in 0..N-1", r.min() >= 0 and r.max() < ranks)
            check("every rank computed points", len(set(r.ravel().tolist())) == ranks,
                  str(sorted(set(r.ravel().tolist()))))
        else:
            check("no rank variable in a serial/merged file", "rank" not in b.variables)


if __name__ == "__main__":
    args = sys.argv[1:]
    ranks = 0
    if "--ranks" in args:
        i = args.index("--ranks")
        ranks = int(args[i + 1])
        del args[i:i + 2]
    if args[0] == "same":
        same(args[1], args[2], ranks)
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("all checks passed")
