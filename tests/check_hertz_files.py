#!/usr/bin/python3
"""Hertz's ellipse in 3D files (docs/case-file.md "Output"): run files carry the global
attributes hertz_a, hertz_b (mm) at hertz_load (N), sweep files the variables hertz_a, hertz_b
at each point's load (`rollsim_post.py map` draws the ellipse of a run: postproc/tests).

  check_hertz_files.py ROLLSIM CASE WORKDIR
      CASE: a small steady 3D case. Expectations from `rollsim check` (Hertz's elliptic
      integrals, printed to 6 digits: relative 1e-5), independent of the files' writer:
      - run file: attributes == check's semi-axes at the case's load; hertz_load == the load;
      - sweep over contact.normal_load [F/2, F] with fields: per point == check's semi-axes
        with --set contact.normal_load=<that load>; their ratio == 2^(-1/3) (a, b grow as
        F^(1/3)); the load's coordinate in N (a 3D load is a force).
"""
import os
import subprocess
import sys

import netCDF4

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def hertz(rollsim, case, *sets):
    out = subprocess.run([rollsim, "check", case, *sets], capture_output=True, text=True,
                         check=True).stdout
    vals = {}
    for line in out.splitlines():
        k, _, rest = line.partition(":")
        vals[k.strip()] = rest.split("#")[0].strip()
    a, b = (float(v) for v in vals["hertz.semi_axes"].strip("[]").split(","))
    return a, b, float(vals["contact.normal_load"])


def close(x, y):
    return abs(x / y - 1) <= 1e-5


def main():
    rollsim, case, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    a, b, load = hertz(rollsim, case)
    run = os.path.join(work, "run.nc")
    subprocess.run([rollsim, "run", case, "-o", run, "--quiet"], check=True)
    with netCDF4.Dataset(run) as ds:
        got = {k: getattr(ds, k, None) for k in ("hertz_a", "hertz_b", "hertz_load")}
    check("run file: hertz_a, hertz_b == rollsim check's semi-axes, hertz_load == the load",
          None not in got.values() and close(got["hertz_a"], a) and close(got["hertz_b"], b)
          and got["hertz_load"] == load, f"{got} vs a = {a}, b = {b}, load = {load}")

    sweep = os.path.join(work, "sweep.nc")
    loads = [load / 2, load]
    subprocess.run([rollsim, "sweep", case, "-o", sweep, "--quiet",
                    f"--set=sweep.contact.normal_load=[{loads[0]!r}, {loads[1]!r}]",
                    "--set=output.fields=[]"], check=True)
    with netCDF4.Dataset(sweep) as ds:
        units = ds["contact_normal_load"].units
        ha, hb = ds["hertz_a"][:].data, ds["hertz_b"][:].data
        dims_ok = ds["hertz_a"].dimensions == ("contact_normal_load",) and \
            ds["hertz_a"].units == "mm"
    check("sweep file: the load's coordinate in N", units == "N", units)
    check("sweep file: hertz_a, hertz_b over the swept load, in mm", dims_ok)
    for k, f in enumerate(loads):
        ak, bk, _ = hertz(rollsim, case, f"--set=contact.normal_load={f!r}")
        check(f"sweep point F = {f:g} N: hertz_a, hertz_b == rollsim check's",
              close(ha[k], ak) and close(hb[k], bk), f"{ha[k]}, {hb[k]} vs {ak}, {bk}")
    ratio = 2 ** (-1 / 3)
    check("sweep: a and b at F/2 are 2^(-1/3) of those at F (Hertz: a, b ~ F^(1/3))",
          abs(ha[0] / ha[1] - ratio) <= 1e-12 and abs(hb[0] / hb[1] - ratio) <= 1e-12,
          f"{ha[0] / ha[1]!r}, {hb[0] / hb[1]!r} vs {ratio!r}")

    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
