#!/usr/bin/python3
"""rollsim.run/check(..., set=...) in Python: a dict or a list of "KEY=VALUE" strings.

  check_python_set.py CASES_DIR
      set= as a list of strings means what the same --set arguments mean on the command line,
      so it must give what the dict gives (check: the resolved keys; run: every variable bit
      for bit, the same code on the same input); anything else raises a TypeError that says
      what set= takes (it was a bare AttributeError: 'list' object has no attribute 'items').
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "postproc"))
import rollsim  # noqa: E402

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def raises_type_error(what, call, words):
    try:
        call()
    except TypeError as e:
        check(f"{what}: TypeError naming {words}", all(w in str(e) for w in words), str(e))
        return
    except Exception as e:  # noqa: BLE001
        check(f"{what}: TypeError", False, f"{type(e).__name__}: {e}")
        return
    check(f"{what}: TypeError", False, "no exception")


def main():
    cases = sys.argv[1]
    default = os.path.join(cases, "default.yaml")
    as_dict = rollsim.check(default, set={"friction.mu": 0.4, "grid.cells": 120})
    as_list = rollsim.check(default, set=["friction.mu=0.4", "grid.cells=120"])
    check("check: list of KEY=VALUE equals the dict",
          as_list == as_dict and as_list["friction.mu"] == 0.4 and as_list["grid.cells"] == 120)
    one = rollsim.check(default, set="friction.mu=0.4")
    check("check: one KEY=VALUE string", one["friction.mu"] == 0.4)
    tup = rollsim.check(default, set=("rolling.creepage={ramp: {from: 0, to: -0.001, start: 0, "
                                      "duration: 1e-4}}",))
    check("check: a YAML value in a tuple item",
          isinstance(tup["rolling.creepage"], dict) and "ramp" in tup["rolling.creepage"],
          repr(tup["rolling.creepage"]))
    raises_type_error("set=0.4", lambda: rollsim.check(default, set=0.4), ["set=", "dict", "KEY=VALUE"])
    raises_type_error("set=['friction.mu']", lambda: rollsim.check(default, set=["friction.mu"]),
                      ["KEY=VALUE", "'friction.mu'"])
    raises_type_error("set=[('friction.mu', 0.4)]",
                      lambda: rollsim.run(default, set=[("friction.mu", 0.4)]), ["KEY=VALUE"])
    carter = os.path.join(cases, "carter2d.yaml")
    a = rollsim.run(carter, set={"rolling.creepage": -3e-4})
    b = rollsim.run(carter, set=["rolling.creepage=-3e-4"])
    same = all(np.array_equal(a[v].values, b[v].values, equal_nan=True) for v in a.variables) and \
        set(a.variables) == set(b.variables)
    check("run: list and dict give the same file", same)
    check("run: the creepage was set", float(b.creepage[-1]) == -3e-4, str(float(b.creepage[-1])))
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
