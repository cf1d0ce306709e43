#!/usr/bin/python3
"""Checks of what a researcher runs into (issue 19), driven by ctest.

  check_usability.py warn-cost constant|varying CELLS -- ROLLSIM ARGS...
      The run prints the long-transient warning: wait for it, interrupt (SIGINT), expect exit 4
      and a file with status 'interrupted'. The warning's numbers must be consistent with its
      own rule: steps left = steps of the window x (t_busy - t)/(window's simulated time), with
      t_busy = min(end, 25 contact lengths 2a/V) for constant inputs (a = Hertz half-width of
      the default contact, 1.00001 mm at V = 30000 mm/s) or the end time otherwise; ETA = steps
      left x ms per step >= 120 s; the hint names steady mode only for constant inputs.
  check_usability.py append FULL.nc FIRST_COPY.nc APPENDED.nc TOL
      APPENDED (FIRST_COPY continued by --restart --append) is one file like FULL (the
      uninterrupted run): the same variables, dimensions, types and global attributes, the same
      output times bit for bit, the first records unchanged bit for bit, every later value
      within TOL (max-norm relative to the variable's max |.|) of FULL, the cell counts equal;
      history = FIRST's history plus one line naming --append and FIRST's status; status complete.
  check_usability.py backup ROLLSIM OUT -- ARGS...
      Running twice into OUT keeps the first file, byte for byte, as OUT~ and says so on stdout.
  check_usability.py cf FILE...
      xarray opens each file; every coordinate variable has units that UDUNITS-2 (the units
      library CF names) parses; the cell counts, converged and regime are integers; every data
      variable has units and long_name.
  check_usability.py case-doc KEYS.tsv DOC.md
      docs/case-file.md and the key table (tests/print_case_keys) name the same keys, with the
      same units, and every choice of a choice key.
"""
import ctypes
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
from queue import Empty, Queue

import numpy as np

failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok  " if ok else "FAIL"), what, detail)
    failures += not ok


def done():
    print(f"{failures} failed")
    sys.exit(1 if failures else 0)


# ---- long-transient warning ---------------------------------------------------------------

WARN = re.compile(r"at t = (\S+) s of (\S+) s, after (\d+) IDA steps in (\S+) s, the last (\d+) "
                  r"steps \((\S+) ms each, (\d+) cells\) covered (\S+) s: (settling to steady "
                  r"rolling needs|the rest needs) about (\S+) steps \((.*)\), ETA .* \((\d+) s\)\.")


def warn_cost(kind, cells, cmd):
    out = cmd[cmd.index("-o") + 1]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # stderr is read by a thread so that a run which never warns is still interrupted at the
    # deadline instead of being waited for to its end.
    queue = Queue()
    reader = threading.Thread(target=lambda: [queue.put(ln) for ln in p.stderr] + [queue.put(None)],
                              daemon=True)
    reader.start()
    lines, deadline = [], time.time() + 90
    while True:
        try:
            line = queue.get(timeout=max(0.0, deadline - time.time()))
        except Empty:
            break
        if line is None:
            break
        lines.append(line)
        if "rollsim: hint:" in line:
            break
    p.send_signal(signal.SIGINT)
    p.wait(timeout=40)
    reader.join(timeout=10)
    while not queue.empty():
        line = queue.get()
        if line is not None:
            lines.append(line)
    text = "".join(lines)
    print(text)
    check("exit 4 after SIGINT (interrupted, records kept)", p.returncode == 4, f"(exit {p.returncode})")
    m = WARN.search(text)
    check("the long-transient warning is printed", m is not None)
    if not m:
        return
    t, end, steps, _, dsteps, ms, ncells, dt, what, left, how, eta = m.groups()
    t, end, dt, ms, left, eta = map(float, (t, end, dt, ms, left, eta))
    check("cells as run", int(ncells) == cells)
    a, V = 1.00001, 30000.0  # Hertz half-width of the default contact (cli_check_default), mm; mm/s
    t_busy = min(end, 25 * 2 * a / V) if kind == "constant" else end
    check(f"{'settling' if kind == 'constant' else 'rest of the run'} named",
          what.startswith("settling") == (kind == "constant"))
    # At constant inputs the density decays by e every L contact lengths 2a/V (printed);
    # a varying input keeps it: the window's density to the end.
    decay = re.search(r"by e every (\S+) contact lengths", how)
    check("the density decays exactly at constant inputs", (decay is not None) == (kind == "constant"),
          how)
    rho = int(dsteps) / dt
    if decay:
        tau = float(decay.group(1)) * 2 * a / V
        want = rho * tau * -math.expm1(-(t_busy - t) / tau)
    else:
        want = rho * (t_busy - t)
    # printed with 6 (t), 3 (dt, left, L) significant digits: 2 % covers the rounding
    check("steps left = window density x decay time x (1 - exp(-(t_busy - t)/decay time))"
          if decay else "steps left = window steps x (t_busy - t)/dt",
          abs(left - want) <= 0.02 * want, f"({left:.4g} vs {want:.4g}, t_busy {t_busy:.6g} s)")
    check("ETA = steps left x time per step", abs(eta - left * ms / 1e3) <= 0.015 * eta + 1,
          f"({eta:.0f} s vs {left * ms / 1e3:.0f} s)")
    check("ETA above the 120 s threshold", eta >= 120.0)
    hint = re.search(r"rollsim: hint: (.*)", text)
    check("a hint follows", hint is not None)
    if hint:
        check("the hint suggests steady mode exactly when the inputs are constant",
              ("simulation.mode: steady" in hint.group(1)) == (kind == "constant"), hint.group(1))
    import netCDF4
    with netCDF4.Dataset(out) as ds:
        check("the file is kept with status 'interrupted'", ds.status == "interrupted", ds.status)
        check("and holds its records", len(ds.dimensions["time"]) >= 1)


# ---- --append ------------------------------------------------------------------------------

def append(full_path, first_path, app_path, tol):
    import netCDF4
    full, first, app = (netCDF4.Dataset(p) for p in (full_path, first_path, app_path))
    for ds in (full, first, app):
        ds.set_auto_mask(False)
    check("same variables as the uninterrupted run", set(app.variables) == set(full.variables),
          str(sorted(set(app.variables) ^ set(full.variables))))
    for name, v in full.variables.items():
        if name in app.variables:
            w = app[name]
            check(f"{name}: same dimensions and type", w.dimensions == v.dimensions and w.dtype == v.dtype)
    check("same dimensions", {k: len(d) for k, d in app.dimensions.items()}
          == {k: len(d) for k, d in full.dimensions.items()})
    check("output times bit for bit", np.array_equal(app["time"][:], full["time"][:]),
          f"({len(app['time'])} records)")
    for att in ("Conventions", "title", "source", "case", "output_fields"):
        check(f"global attribute {att} as the first run wrote it", app.getncattr(att) == first.getncattr(att))
    n1 = len(first["time"])
    worst = {}
    for name, v in app.variables.items():
        if "time" not in v.dimensions or name == "time":
            continue
        a, f1, ref = np.asarray(v[:]), np.asarray(first[name][:]), np.asarray(full[name][:])
        check(f"{name}: the first {n1} records unchanged", np.array_equal(a[:n1], f1))
        if a.dtype.kind in "iu":
            check(f"{name}: integers equal the uninterrupted run's", np.array_equal(a, ref))
            continue
        scale = np.max(np.abs(ref))
        worst[name] = np.max(np.abs(a - ref)) / scale if scale > 0 else np.max(np.abs(a - ref))
    print("largest relative deviations:", ", ".join(f"{k} {e:.2g}" for k, e in worst.items()))
    check(f"every value within {tol:g} of the uninterrupted run", all(e <= tol for e in worst.values()))
    hist = app.history.split("\n")
    check("history: the first run's lines, then one more", hist[:-1] == first.history.split("\n")
          and len(hist) == len(first.history.split("\n")) + 1, repr(app.history))
    check("the new line names --append and the old status",
          "--append" in hist[-1] and f"continued in {os.path.basename(app_path)}" in hist[-1]
          or ("--append" in hist[-1] and "continued in" in hist[-1] and "status was 'complete'" in hist[-1]),
          hist[-1])
    check("status complete", app.status == "complete", app.status)


# ---- OUT.nc~ -------------------------------------------------------------------------------

def backup(rollsim, out, args):
    for f in (out, out + "~"):
        if os.path.exists(f):
            os.remove(f)
    first = subprocess.run([rollsim] + args + ["-o", out], capture_output=True, text=True)
    check("first run", first.returncode == 0, first.stderr)
    with open(out, "rb") as f:
        before = f.read()
    second = subprocess.run([rollsim] + args + ["-o", out], capture_output=True, text=True)
    print(second.stdout)
    check("second run", second.returncode == 0, second.stderr)
    check("the first file is kept as OUT~, byte for byte",
          os.path.exists(out + "~") and open(out + "~", "rb").read() == before)
    check("the summary says so", f"{out}~" in second.stdout)


# ---- CF: xarray, integer counts, units -----------------------------------------------------

def udunits():
    lib = ctypes.CDLL("libudunits2.so.0")
    lib.ut_set_error_message_handler.restype = ctypes.c_void_p
    lib.ut_set_error_message_handler.argtypes = [ctypes.c_void_p]
    lib.ut_set_error_message_handler(ctypes.cast(lib.ut_ignore, ctypes.c_void_p))
    lib.ut_read_xml.restype = ctypes.c_void_p
    lib.ut_read_xml.argtypes = [ctypes.c_char_p]
    system = lib.ut_read_xml(None)
    if not system:
        raise RuntimeError("UDUNITS-2: cannot read its unit database")
    lib.ut_parse.restype = ctypes.c_void_p
    lib.ut_parse.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    lib.ut_free.argtypes = [ctypes.c_void_p]

    def valid(text):
        unit = lib.ut_parse(system, text.encode(), 0)  # UT_ASCII
        if unit:
            lib.ut_free(unit)
        return bool(unit)
    return valid


INTEGERS = ("n_exterior", "n_adhesion", "n_slip", "n_plastic", "converged", "regime")


def cf(paths):
    import xarray as xr
    valid = udunits()
    check("UDUNITS-2 rejects a non-unit", not valid("Hertz half-widths") and valid("N/mm^2"))
    for path in paths:
        with xr.open_dataset(path) as ds:
            for name, c in ds.coords.items():
                units = c.attrs.get("units", "")
                check(f"{os.path.basename(path)}: coordinate {name} has valid units",
                      bool(units) and valid(units), repr(units))
            ints = [v for v in INTEGERS if v in ds.variables]
            for v in ints:
                check(f"{os.path.basename(path)}: {v} is an integer", ds[v].dtype.kind == "i",
                      str(ds[v].dtype))
            check(f"{os.path.basename(path)}: has cell counts", "n_slip" in ds.variables)
            for name, v in ds.data_vars.items():
                check(f"{os.path.basename(path)}: {name} has units and long_name",
                      "units" in v.attrs and "long_name" in v.attrs)


# ---- docs/case-file.md -----------------------------------------------------------------------

def case_doc(keys_tsv, doc):
    table = {}
    with open(keys_tsv) as f:
        for line in f:
            path, kind, unit, choices = line.rstrip("\n").split("\t")
            table[path] = (kind, unit, [c for c in choices.split(",") if c])
    text = open(doc).read()
    rows = {}
    for line in text.splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)]  # a \| inside a cell stays
        m = re.fullmatch(r"`([A-Za-z0-9_.]+)`", cells[1]) if len(cells) >= 5 and cells[0] == "" else None
        if m:
            rows[m.group(1)] = (cells[2], cells[3], cells[4])
    values = {k for k, (kind, _, _) in table.items() if kind not in ("section", "opaque")}
    check("every key of the table is in the doc", not (values - set(rows)), str(sorted(values - set(rows))))
    check("the doc names no key the table lacks", not (set(rows) - set(table)), str(sorted(set(rows) - set(table))))
    for key in sorted(values & set(rows)):
        kind, unit, choices = table[key]
        doc_unit = rows[key][1]
        # a force per width in 2D is a total force in 3D: "N/mm (3D: N)" (rs_case_key_unit_in)
        want = [unit or "—"] + (["N/mm (3D: N)"] if unit == "N/mm" else [])
        check(f"{key}: unit", doc_unit in want, f"(doc {doc_unit!r}, table {unit!r})")
        for c in choices:
            check(f"{key}: choice {c} documented", f"`{c}`" in rows[key][0] + rows[key][2])
    for key, (kind, _, _) in table.items():
        if kind in ("section", "opaque"):
            check(f"section {key}: has a heading", re.search(rf"^#+ `?{key}:?`?", text, re.M) is not None)


if __name__ == "__main__":
    what = sys.argv[1]
    if what == "warn-cost":
        i = sys.argv.index("--")
        warn_cost(sys.argv[2], int(sys.argv[3]), sys.argv[i + 1:])
    elif what == "append":
        append(sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]))
    elif what == "backup":
        i = sys.argv.index("--")
        backup(sys.argv[2], sys.argv[3], sys.argv[i + 1:])
    elif what == "cf":
        cf(sys.argv[2:])
    elif what == "case-doc":
        case_doc(sys.argv[2], sys.argv[3])
    else:
        sys.exit(f"unknown check {what}")
    done()
