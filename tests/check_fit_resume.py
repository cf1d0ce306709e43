#!/usr/bin/python3
"""rollsim fit --resume (issue 46, item 4): an interrupted fit continued from its file.

  check_fit_resume.py ROLLSIM CASE WORKDIR [MPIRUN]

CASE (cases/fit_creep_curve.yaml, 3 parameters, 41 noisy points) and its CSV are copied to
WORKDIR, so that the data can be changed under a file. The fit is run uninterrupted, and
once more interrupted with SIGINT as soon as its file shows a best point after at least 10
evaluations (status "running"). Then:

- Refusals, each exit 2 with its reason, the file untouched (bytes and mtime): other --set
  values, another case (cases/fit_twin_disc.yaml), changed measurements, a sweep file, a
  truncated file, a missing file (not created).
- The resume: exit 0, status complete, the file's evaluations are the stored ones plus the
  new ones the summary reports, the new ones fewer than the uninterrupted fit's total (it
  starts at the best point instead of the first guess), the stored start kept, and the
  history line says what was resumed. The optimum is the uninterrupted fit's within 1 % of
  the standard errors: lmder stops when the relative reduction of |r|^2 falls below
  ftol = 1e-8, so each stop lies above the minimum by about 1e-8 |r|^2 (a few times that at
  most); in the metric of J^T J that is a distance dp with dp^T C^-1 dp ~ 1e-8 (m - n)
  = 3.8e-7 (C = s^2 (J^T J)^-1, s^2 = |r|^2/(m - n)), i.e. |dp_k| <~ 6e-4 sigma_k per
  run (2e-3 sigma_k with a factor 10 to spare), and the two stops differ by at most the sum.
  The residual norms then agree to 1e-7 relative (both within ~1e-8 of the minimum's |r|^2).
- A resume of the complete file: exit 0, "nothing to resume", the file untouched.
- With MPIRUN: a refusal under mpirun -n 2 (exit 2, no rank left waiting), and the resume
  of a copy of the interrupted file under mpirun -n 2 gives the serial resume bit for bit
  (each Jacobian column is computed whole on one rank, as in the fit_creep_mpi2 test).
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import netCDF4
import numpy as np

failures = []


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def read(path):
    with netCDF4.Dataset(path) as ds:
        return {"fitted": ds["fitted"][:].data.copy(), "start": ds["start"][:].data.copy(),
                "se": ds["standard_error"][:].data.copy(), "norm": float(ds.residual_norm),
                "status": ds.status, "evaluations": int(ds.evaluations),
                "history": ds.history}


def run(cmd, timeout=120):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    print("$ " + " ".join(cmd) + "\n" + p.stdout + p.stderr)
    return p


def fingerprint(path):
    if not os.path.exists(path):
        return None
    st = os.stat(path)
    with open(path, "rb") as f:
        return f.read(), st.st_mtime_ns


def refused(what, cmd, path, reason):
    before = fingerprint(path)
    p = run(cmd)
    check(f"{what}: exit 2", p.returncode == 2, str(p.returncode))
    check(f"{what}: says why", re.search(reason, p.stderr) is not None, p.stderr.strip())
    check(f"{what}: the file untouched", fingerprint(path) == before)
    check(f"{what}: no .part left", not os.path.exists(path + ".part"))


def interrupted_fit(rollsim, case, out):
    p = subprocess.Popen([rollsim, "fit", case, "-o", out, "--quiet"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while p.poll() is None and time.time() < deadline:
        try:
            with netCDF4.Dataset(out) as ds:
                if ds.status == "running" and int(ds.evaluations) >= 10:
                    break
        except OSError:
            pass  # not written yet
        time.sleep(0.02)
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=120)
    print(stdout + stderr)
    return p.returncode


def main():
    rollsim, case, work = sys.argv[1:4]
    mpirun = sys.argv[4] if len(sys.argv) > 4 else None
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(os.path.join(work, "data"))
    here = os.path.dirname(os.path.abspath(case))
    mycase = os.path.join(work, "case.yaml")
    shutil.copy(case, mycase)
    csv = os.path.join(work, "data", "creep_curve_measured.csv")
    shutil.copy(os.path.join(here, "data", "creep_curve_measured.csv"), csv)
    full, out = os.path.join(work, "full.nc"), os.path.join(work, "resumed.nc")

    p = run([rollsim, "fit", mycase, "-o", full, "--quiet"])
    check("uninterrupted fit: exit 0", p.returncode == 0, str(p.returncode))
    ref = read(full)

    code = interrupted_fit(rollsim, mycase, out)
    check("interrupted fit: exit 4", code == 4, str(code))
    stored = read(out)
    check("interrupted file: status interrupted", stored["status"] == "interrupted",
          stored["status"])
    check("interrupted after some but not all evaluations",
          10 <= stored["evaluations"] < ref["evaluations"],
          f"{stored['evaluations']} of {ref['evaluations']}")

    fit = [rollsim, "fit", mycase, "-o", out, "--quiet", "--resume"]
    refused("other --set", fit + ["--set", "rolling.velocity=30001"], out,
            "cannot resume: the file is of another case or other --set values")
    refused("another case", [rollsim, "fit", os.path.join(here, "fit_twin_disc.yaml"), "-o", out,
                             "--quiet", "--resume"], out, "cannot resume: the file is of another case")
    with open(csv) as f:
        original = f.read()
    lines = original.rstrip("\n").split("\n")
    x, y = lines[-1].split(",")
    lines[-1] = f"{x},{float(y) + 0.001!r}"
    with open(csv, "w") as f:
        f.write("\n".join(lines) + "\n")
    refused("changed measurements", fit, out, "cannot resume: its data differ from")
    with open(csv, "w") as f:
        f.write(original)
    sweep = os.path.join(work, "sweep.nc")
    p = run([rollsim, "sweep", mycase, "-o", sweep, "--quiet", "--set",
             "sweep.rolling.creepage=[0, -0.01]"])
    check("a sweep file written", p.returncode == 0, str(p.returncode))
    refused("a sweep file", [rollsim, "fit", mycase, "-o", sweep, "--quiet", "--resume"], sweep,
            "cannot resume: not a fit file")
    trunc = os.path.join(work, "truncated.nc")
    shutil.copy(out, trunc)
    with open(trunc, "r+b") as f:
        f.truncate(os.path.getsize(trunc) - 200)
    refused("a truncated file", [rollsim, "fit", mycase, "-o", trunc, "--quiet", "--resume"],
            trunc, r"cannot resume: the file is truncated \(\d+ of \d+ bytes\)")
    missing = os.path.join(work, "missing.nc")
    refused("a missing file", [rollsim, "fit", mycase, "-o", missing, "--quiet", "--resume"],
            missing, "cannot resume: no such file")
    if mpirun:
        refused("under MPI, other --set",
                [mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2"] + fit
                + ["--set", "rolling.velocity=30001"], out, "cannot resume: the file is of another")

    copy = os.path.join(work, "resumed_mpi.nc")
    shutil.copy(out, copy)
    p = run(fit)
    check("resumed fit: exit 0", p.returncode == 0, str(p.returncode))
    res = read(out)
    check("resumed file: status complete", res["status"] == "complete", res["status"])
    m = re.search(r"resumed: (\d+) evaluations were in the file, (\d+) new", p.stdout)
    check("the summary says what was resumed", m is not None)
    if m:
        before, new = int(m.group(1)), int(m.group(2))
        check("the stored evaluations counted on", before == stored["evaluations"],
              f"{before} vs {stored['evaluations']}")
        check("the file's evaluations: stored + new", res["evaluations"] == before + new,
              f"{res['evaluations']} vs {before} + {new}")
        check(f"fewer new evaluations ({new}) than the uninterrupted fit's {ref['evaluations']}",
              new < ref["evaluations"])
    check("the stored start kept", np.array_equal(res["start"], stored["start"]))
    check("history: the resume's line",
          re.search(r"--resume \(resumed from %d evaluations, residual [0-9.e+-]+\)$"
                    % stored["evaluations"], res["history"]) is not None, res["history"])
    check("history: the first run's line kept", res["history"].startswith(stored["history"]))
    z = np.abs(res["fitted"] - ref["fitted"]) / ref["se"]
    check("the uninterrupted fit's optimum within 0.01 standard errors",
          np.all(z <= 0.01), f"|difference|/sigma = {z}")
    check("the same residual norm to 1e-7", abs(res["norm"] / ref["norm"] - 1) <= 1e-7,
          f"{res['norm']!r} vs {ref['norm']!r}")

    if mpirun:
        p = run([mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2", rollsim, "fit",
                 mycase, "-o", copy, "--quiet", "--resume"])
        check("under MPI, the resume: exit 0", p.returncode == 0, str(p.returncode))
        with netCDF4.Dataset(out) as a, netCDF4.Dataset(copy) as b:
            for v in ("fitted", "standard_error", "simulated"):
                check(f"under MPI, the resume: {v} bitwise the serial resume's",
                      np.array_equal(a[v][:].data.view(np.uint64), b[v][:].data.view(np.uint64)))
            check("under MPI, the resume: the same evaluations",
                  int(a.evaluations) == int(b.evaluations))

    before = fingerprint(out)
    p = run(fit)
    check("resume of a complete file: exit 0", p.returncode == 0, str(p.returncode))
    check("resume of a complete file: says so", "nothing to resume" in p.stdout)
    check("resume of a complete file: the file untouched", fingerprint(out) == before)

    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("all checks passed")


if __name__ == "__main__":
    main()
