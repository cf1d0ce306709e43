#!/usr/bin/python3
"""The Python package (postproc/rollsim, issue 16) against the command line.

  check_python.py ROLLSIM WORKDIR CASE...
      For each case: `rollsim run CASE -o F` and rollsim.run(CASE) give the same numbers (every
      variable bit for bit: the package runs the same code on the same input and loads the file
      the command line writes; relative difference 0), and the same attributes but history and
      writer (the command line and the writing process).
      A sweep (creep_curves.yaml cut to 2 lines) likewise; a dict case equals its file; two runs
      in one process are identical; invalid cases raise CaseError with the command line's
      message (its stderr line) and status 2.
"""
import os
import subprocess
import sys

import numpy as np
import xarray as xr
import yaml

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "postproc"))
import rollsim  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def bits(a):
    a = np.asarray(a)
    return a.view(np.uint64) if a.dtype == np.float64 else a


def same(label, cli, py):
    missing = set(cli.variables) ^ set(py.variables)
    check(f"{label}: same variables", not missing, str(sorted(missing)))
    worst = 0.0
    for name in cli.variables:
        if name not in py.variables:
            continue
        a, b = cli[name].values, py[name].values
        if a.dtype.kind == "f":
            eq = a.shape == b.shape and np.array_equal(bits(a), bits(b))
            if not eq and a.shape == b.shape:
                with np.errstate(invalid="ignore", divide="ignore"):
                    worst = max(worst, float(np.nanmax(np.abs(a - b) / np.maximum(np.abs(a), 1e-300))))
        else:
            eq = a.shape == b.shape and np.array_equal(a, b)
        if not eq:
            check(f"{label}: {name} equal", False, f"max relative difference {worst:.3g}")
    check(f"{label}: every variable bitwise equal", worst == 0.0 and not missing)
    for att in set(cli.attrs) | set(py.attrs):
        if att not in ("history", "writer"):
            check(f"{label}: attribute {att}", cli.attrs.get(att) == py.attrs.get(att))


def cli_file(rollsim_bin, args, out):
    if os.path.exists(out):
        os.remove(out)
    subprocess.run([rollsim_bin] + args + ["-o", out, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    with xr.open_dataset(out) as ds:
        return ds.load()


def main():
    rollsim_bin, work, cases = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(work, exist_ok=True)
    for case in cases:
        name = os.path.basename(case)
        same(name, cli_file(rollsim_bin, ["run", case], os.path.join(work, name + ".nc")),
             rollsim.run(case))
    # a sweep with set= overrides
    creep = [c for c in cases if c.endswith("creep_curves.yaml")][0]
    sets = {"sweep.plasticity.tau_c0": [200.0, 350.0], "sweep.plasticity.k_rel": [0.6],
            "sweep.rolling.creepage": {"linspace": [0, -0.02, 11]}}
    args = ["sweep", creep] + [x for k, v in sets.items()
                               for x in ("--set", f"{k}={rollsim._yaml_value(v)}")]
    same("sweep with set=", cli_file(rollsim_bin, args, os.path.join(work, "sweep.nc")),
         rollsim.sweep(creep, set=sets))
    # a progress callback: called once per point, the same numbers
    calls = []
    same("sweep with progress", cli_file(rollsim_bin, args, os.path.join(work, "sweep2.nc")),
         rollsim.sweep(creep, set=sets, progress=lambda d, t: calls.append((d, t))))
    check("progress called once per point, in order",
          calls == [(k, 22) for k in range(1, 23)], str(calls[:3]))
    # a dict case: the same numbers as its file (the case text differs: not compared)
    carter = [c for c in cases if c.endswith("carter2d.yaml")][0]
    with open(carter) as f:
        d = yaml.safe_load(f)
    a, b = rollsim.run(carter), rollsim.run(d)
    check("dict case = file case (Fx, px bitwise)",
          np.array_equal(bits(a["Fx"].values), bits(b["Fx"].values))
          and np.array_equal(bits(a["px"].values), bits(b["px"].values)))
    c = rollsim.run(carter)
    check("two runs in one process identical",
          all(np.array_equal(bits(a[v].values), bits(c[v].values)) for v in a.variables
              if a[v].dtype.kind == "f"))
    check("check() returns derived values", abs(rollsim.check(carter)["hertz.half_width"] - 1.0) < 1e-4)
    # invalid input: the command line's message
    bad_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bad_inputs")
    for bad in ("both_k_tau_k_rel.yaml", "cells_hex.yaml", "friction_law.yaml"):
        path = os.path.join(bad_dir, bad)
        p = subprocess.run([rollsim_bin, "run", path, "-o", os.path.join(work, "bad.nc")],
                           capture_output=True, text=True)
        try:
            rollsim.run(path)
            check(f"{bad}: raises", False)
        except rollsim.CaseError as e:
            check(f"{bad}: CaseError with the command line's message",
                  str(e) == p.stderr.strip() and e.status == 2 == p.returncode,
                  f"{str(e)!r} vs {p.stderr.strip()!r}")
    try:
        rollsim.run("contact: {normal_load: -1}\n")
        check("YAML text error raises", False)
    except rollsim.CaseError as e:
        check("YAML text error names <case>:line: key", str(e).startswith("<case>:1: contact.normal_load"),
              str(e))


if __name__ == "__main__":
    main()
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("all checks passed")
