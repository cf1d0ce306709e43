#!/usr/bin/python3
"""Resuming a killed sweep (issue 46): a sweep killed with SIGKILL at three moments, then
`rollsim sweep ... --resume`, must leave the file an uninterrupted sweep writes, variable by
variable and bit for bit: the lines complete in the file are the ones an uninterrupted sweep
wrote (the same code from the same inputs), and every other line is computed again from its
first point (lines start from rest, so nothing of the killed run carries over).
`rollsim status` must say how far the killed file got, and a resume that does not belong to
the file must exit 2 and leave it untouched (same bytes and modification time).

  check_resume.py kill BIN CASE DIR [--part K/N] [--mpi MPIRUN] -- SETS...
      reference, three kills (after 20, 45 and 70 % of an uninterrupted run's time), status,
      resume, comparison
  check_resume.py refuse BIN CASE DIR -- SETS...
      bad resumes: other --set, other case, other part, not a sweep file, a truncated file
  check_resume.py term BIN CASE DIR -- SETS...
      SIGTERM (a batch system's time limit) during a serial sweep, then resume, comparison
  check_resume.py status BIN CASE DIR [--no-python] -- SETS...
      rollsim status and rollsim.status (Python) of a complete, a killed and a failed sweep
      (cases/startup.yaml with solver.max_steps 3: every transient point stops before its
      end), and of a killed part
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import netCDF4
import numpy as np

failures = []
FRACTIONS = (0.2, 0.45, 0.7)


def check(what, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + what + (": " + detail if detail else ""))
    if not ok:
        failures.append(what)


def counts(path):
    with netCDF4.Dataset(path) as d:
        d.set_auto_mask(False)
        c = d.variables["converged"][:]
        part = int(d.getncattr("part")) if "part" in d.ncattrs() else 0
        parts = int(d.getncattr("parts")) if "parts" in d.ncattrs() else 0
    lines = c.reshape(-1, c.shape[-1])
    if parts:
        lines = lines[(part - 1)::parts]
    return int((lines != netCDF4.default_fillvals["i4"]).sum()), lines.size


def same(ref, other):
    """Every variable of ref bit for bit in other (rank aside: it says who computed)."""
    with netCDF4.Dataset(ref) as a, netCDF4.Dataset(other) as b:
        a.set_auto_mask(False)
        b.set_auto_mask(False)
        bad = []
        for name, va in a.variables.items():
            if name == "rank":
                continue
            if name not in b.variables:
                bad.append(name + " missing")
                continue
            x, y = va[:], b.variables[name][:]
            if x.dtype.kind == "f":
                w = np.uint64 if x.itemsize == 8 else np.uint32
                eq = x.shape == y.shape and np.array_equal(x.view(w), y.view(w))
            else:
                eq = x.shape == y.shape and np.array_equal(x, y)
            if not eq:
                bad.append(name)
        check(f"{other}: {len(a.variables)} variables bitwise equal to {ref}", not bad, ", ".join(bad))
        check(f"{other}: case attribute equal", a.getncattr("case") == b.getncattr("case"))
        check(f"{other}: status complete", b.getncattr("status") == "complete", b.getncattr("status"))
        check(f"{other}: history says it was resumed", "resumed:" in b.getncattr("history"))


def descendants(pid):
    kids = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
                kids.setdefault(ppid, []).append(int(d))
            except (OSError, IndexError, ValueError):
                pass
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        for k in kids.get(p, []):
            out.append(k)
            todo.append(k)
    return out


def kill_rank1(mpirun_pid):
    """SIGKILL the rollsim process of MPI rank 1 (mpirun then aborts the job)."""
    for p in descendants(mpirun_pid):
        try:
            with open(f"/proc/{p}/environ", "rb") as f:
                env = f.read().split(b"\0")
            with open(f"/proc/{p}/comm") as f:
                comm = f.read().strip()
        except OSError:
            continue
        if comm == "rollsim" and (b"OMPI_COMM_WORLD_RANK=1" in env or b"PMI_RANK=1" in env):
            os.kill(p, signal.SIGKILL)
            return True
    return False


def kill(b, case, d, part, mpirun, sets):
    tag = "mpi" if mpirun else f"part{part.replace('/', 'of')}" if part else "serial"
    extra = ["--part", part] if part else []
    ref = os.path.join(d, f"{tag}_ref.nc")
    cmd = [b, "sweep", case, "--quiet"] + extra + sets
    launch = [mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2"] if mpirun else []
    subprocess.run(cmd + ["-o", ref], check=True, stdout=subprocess.DEVNULL)
    # the kills at fixed fractions of an uninterrupted run's time on this machine now
    t0 = time.monotonic()
    subprocess.run(launch + cmd + ["-o", os.path.join(d, f"{tag}_timed.nc")], check=True,
                   stdout=subprocess.DEVNULL)
    took = time.monotonic() - t0
    print(f"uninterrupted: {took:.2f} s")
    for k, f in enumerate(FRACTIONS):
        out = os.path.join(d, f"{tag}_killed_{k + 1}.nc")
        t = round(f * took, 2)
        for attempt in range(4):  # a busy machine: the run may end before the kill, kill earlier
            for name in (out, out + "~"):
                if os.path.exists(name):
                    os.remove(name)
            p = subprocess.Popen(launch + cmd + ["-o", out], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL)
            time.sleep(t)
            if mpirun:
                killed = kill_rank1(p.pid)
            else:
                killed = p.poll() is None
                p.send_signal(signal.SIGKILL)
            rc = p.wait(timeout=60)
            if killed and rc != 0 and counts(out)[0] < counts(out)[1]:
                break  # killed with points missing (a slow machine may have written them all)
            print(f"the run ended before the kill at {t} s: again, killed earlier")
            t = round(t * 0.6, 2)
        check(f"killed at {t} s (exit {rc})", killed and rc != 0)
        n, m = counts(out)
        check(f"killed at {t} s: {n} of {m} points in the file, some missing", n < m)
        s = subprocess.run([b, "status", out], capture_output=True, text=True)
        check(f"rollsim status of the killed file: {s.stdout.strip()}",
              s.returncode == 0 and s.stdout.startswith(f"incomplete: {n} of {m} points")
              and "status: running, but its writer, process " in s.stdout
              and "is gone: killed" in s.stdout
              and "last written at " in s.stdout)
        r = subprocess.run(launch + cmd + ["-o", out, "--resume"], capture_output=True, text=True)
        check(f"resume after the kill at {t} s: exit {r.returncode}", r.returncode == 0,
              r.stderr.strip())
        kept = [ln for ln in r.stdout.splitlines() if ln.startswith("resumed:")]
        check("the summary says what was kept", len(kept) == 1, kept[0] if kept else r.stdout)
        same(ref, out)
        s = subprocess.run([b, "status", out], capture_output=True, text=True)
        check(f"rollsim status after the resume: {s.stdout.strip()}",
              s.returncode == 0 and s.stdout.startswith(f"complete: {m} of {m} points"))
    shutil.copyfile(out, os.path.join(d, f"{tag}_resumed.nc"))


def untouched_after(what, path, cmd, expect):
    st = os.stat(path)
    with open(path, "rb") as f:
        before = f.read()
    time.sleep(0.05)
    r = subprocess.run(cmd, capture_output=True, text=True)
    with open(path, "rb") as f:
        after = f.read()
    check(f"{what}: exit 2", r.returncode == 2, f"exit {r.returncode}: {r.stderr.strip()}")
    check(f"{what}: message '{expect}'", expect in r.stderr, r.stderr.strip())
    check(f"{what}: file untouched", before == after and os.stat(path).st_mtime_ns == st.st_mtime_ns)
    check(f"{what}: no backup made", not os.path.exists(path + "~"))


def refuse(b, case, d, sets):
    """Bad resumes of a killed file: each exits 2 with a clear message, the file untouched."""
    shutil.rmtree(d)  # no files (or backups) of an earlier run
    os.makedirs(d)
    out = os.path.join(d, "refuse.nc")
    for f in (out, out + "~"):
        if os.path.exists(f):
            os.remove(f)
    p = subprocess.Popen([b, "sweep", case, "--quiet", "-o", out] + sets, stdout=subprocess.DEVNULL)
    time.sleep(0.8)
    p.send_signal(signal.SIGKILL)
    p.wait()
    base = [b, "sweep", case, "--quiet", "-o", out, "--resume"]
    untouched_after("other --set", out, base + sets + ["--set", "friction.mu=0.31"],
                    "another case or other --set values")
    other = os.path.join(d, "other_case.yaml")
    with open(case) as f:
        text = f.read()
    with open(other, "w") as f:
        f.write(text.replace("title: \"", "title: \"another "))
    untouched_after("other case file", out, [b, "sweep", other, "--quiet", "-o", out, "--resume"] + sets,
                    "another case or other --set values")
    untouched_after("whole file resumed as a part", out, base + sets + ["--part", "2/3"],
                    "the file is the whole sweep, not part 2/3")
    part = os.path.join(d, "refuse_part.nc")
    subprocess.run([b, "sweep", case, "--quiet", "-o", part, "--part", "1/3"] + sets, check=True,
                   stdout=subprocess.DEVNULL)
    untouched_after("part 1/3 resumed as part 2/3", part,
                    [b, "sweep", case, "--quiet", "-o", part, "--resume", "--part", "2/3"] + sets,
                    "the file is part 1/3, not 2/3")
    untouched_after("part resumed as the whole sweep", part,
                    [b, "sweep", case, "--quiet", "-o", part, "--resume"] + sets,
                    "resume it with --part 1/3")
    text_file = os.path.join(d, "not_netcdf.nc")
    with open(text_file, "w") as f:
        f.write("not a netCDF file\n")
    untouched_after("a text file", text_file,
                    [b, "sweep", case, "--quiet", "-o", text_file, "--resume"] + sets,
                    "not a readable sweep file")
    other_axes = os.path.join(d, "other_axes.nc")
    subprocess.run([b, "sweep", case, "--quiet", "-o", other_axes] + sets
                   + ["--set", "sweep={rolling.creepage: [0, -0.001]}"], check=True,
                   stdout=subprocess.DEVNULL)
    untouched_after("a sweep file of other swept keys", other_axes,
                    [b, "sweep", case, "--quiet", "-o", other_axes, "--resume"] + sets,
                    "cannot resume: not a sweep file of 3 swept keys")
    trunc = os.path.join(d, "truncated.nc")
    shutil.copyfile(out, trunc)
    with open(trunc, "r+b") as f:
        f.truncate(os.path.getsize(trunc) * 2 // 3)
    untouched_after("a truncated file", trunc,
                    [b, "sweep", case, "--quiet", "-o", trunc, "--resume"] + sets,
                    "the file is truncated")
    s = subprocess.run([b, "status", trunc], capture_output=True, text=True)
    check("rollsim status of a truncated file: exit 2", s.returncode == 2 and "truncated" in s.stderr,
          s.stderr.strip())
    missing = os.path.join(d, "missing.nc")
    if os.path.exists(missing):
        os.remove(missing)
    r = subprocess.run([b, "sweep", case, "--quiet", "-o", missing, "--resume"] + sets,
                       capture_output=True, text=True)
    check("resume of a missing file: exit 2, nothing written",
          r.returncode == 2 and "no such file" in r.stderr and not os.path.exists(missing),
          r.stderr.strip())


def status(b, case, d, sets, python=True):
    if python:
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                        "postproc"))
        import rollsim

    def both(path, line, state, written, points, failed, part=0, parts=0):
        s = subprocess.run([b, "status", path], capture_output=True, text=True)
        check(f"rollsim status {os.path.basename(path)}: {s.stdout.strip()}",
              s.returncode == 0 and s.stdout.startswith(line), s.stderr.strip())
        c = subprocess.run([b, "check", path], capture_output=True, text=True)
        check("rollsim check FILE.nc says the same", c.returncode == 0 and c.stdout == s.stdout)
        if not python:
            return
        r = rollsim.status(path)
        check(f"rollsim.status: {r}",
              (r["state"], r["written"], r["points"], r["failed"], r["part"], r["parts"])
              == (state, written, points, failed, part, parts)
              and r["summary"] == s.stdout.strip())

    full = os.path.join(d, "complete.nc")
    subprocess.run([b, "sweep", case, "--quiet", "-o", full] + sets, check=True,
                   stdout=subprocess.DEVNULL)
    both(full, "complete: 279 of 279 points\n", "complete", 279, 279, 0)
    killed = os.path.join(d, "killed.nc")
    if os.path.exists(killed):
        os.remove(killed)
    p = subprocess.Popen([b, "sweep", case, "--quiet", "-o", killed] + sets,
                         stdout=subprocess.DEVNULL)
    # killed as soon as the file holds a point (its first batch), however slow the machine
    deadline = time.monotonic() + 120
    while p.poll() is None and time.monotonic() < deadline:
        try:
            if counts(killed)[0] > 0:
                break
        except (OSError, RuntimeError, KeyError):
            pass  # not created yet, or its header is being written
        time.sleep(0.05)
    # while it runs: its writer, this very process, is named
    s = subprocess.run([b, "status", killed], capture_output=True, text=True)
    check(f"rollsim status while the sweep runs: {s.stdout.strip()}",
          p.poll() is not None
          or f"(status: running: process {p.pid} on this host is writing it)" in s.stdout)
    p.send_signal(signal.SIGKILL)
    p.wait()
    n, m = counts(killed)
    check(f"killed after its first batch: {n} of {m} points", 0 < n < m)
    both(killed, f"incomplete: {n} of {m} points (status: running, but its writer, process "
         f"{p.pid} on this host, is gone: killed), last written at ", "incomplete", n, m, 0)
    part = os.path.join(d, "part.nc")
    subprocess.run([b, "sweep", case, "--quiet", "-o", part, "--part", "3/4"] + sets, check=True,
                   stdout=subprocess.DEVNULL)
    # lines 2 and 6 of the 9 (l mod 4 = 2), 31 points each
    both(part, "complete: 62 of 62 points of part 3/4", "complete", 62, 62, 0, 3, 4)
    failed = os.path.join(d, "failed.nc")
    startup = os.path.join(os.path.dirname(case), "startup.yaml")
    r = subprocess.run([b, "sweep", startup, "--quiet", "-o", failed, "--set",
                        "sweep={friction.mu: [0.3, 0.35]}", "--set", "solver.max_steps=3"],
                       capture_output=True, text=True)
    check("the sweep with solver.max_steps 3 fails: exit 3", r.returncode == 3, r.stderr.strip())
    both(failed, "failed: 2 of 2 points did not converge (NaN in the file)", "failed", 2, 2, 2)


def term(b, case, d, sets, mpirun=None):
    """SIGTERM (a batch system's time limit) during a serial sweep: exit 4, status
    "interrupted", every finished point kept (the batch is written at close); the resume
    then gives the uninterrupted file bit for bit. With mpirun: Ctrl-C, SIGINT to the
    job's process group as a terminal sends it; every rank stops after its current point
    and rank 0 closes the file with status "interrupted", unless mpirun's grace period
    ends first and it kills the ranks (then the file is as after a SIGKILL): either way the
    resume gives the uninterrupted file bit for bit."""
    tag = "int_mpi" if mpirun else "term"
    ref = os.path.join(d, f"{tag}_ref.nc")
    out = os.path.join(d, f"{tag}.nc")
    launch = [mpirun, "--oversubscribe", "--allow-run-as-root", "-n", "2"] if mpirun else []
    cmd = launch + [b, "sweep", case, "--quiet"] + sets
    name = "SIGINT to the mpirun job" if mpirun else "SIGTERM"
    t0 = time.monotonic()
    subprocess.run(cmd + ["-o", ref], check=True, stdout=subprocess.DEVNULL)
    t = round(0.45 * (time.monotonic() - t0), 2)
    for attempt in range(4):  # a busy machine: the run may end before the signal, send earlier
        for f in (out, out + "~"):
            if os.path.exists(f):
                os.remove(f)
        p = subprocess.Popen(cmd + ["-o", out], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=bool(mpirun))
        time.sleep(t)
        running = p.poll() is None
        if mpirun:
            os.killpg(p.pid, signal.SIGINT)
        else:
            p.send_signal(signal.SIGTERM)
        rc = p.wait(timeout=120)
        if running and rc != 0 and counts(out)[0] < counts(out)[1]:
            break
        t = round(t * 0.6, 2)
    with netCDF4.Dataset(out) as f:
        st = f.getncattr("status")
    if mpirun:  # mpirun reports a rank's exit 4 as its own exit 1
        check(f"{name} at {t} s: nonzero exit", rc != 0, f"exit {rc}")
        check("the file's status is 'interrupted', or 'running' if mpirun killed the ranks",
              st in ("interrupted", "running"), st)
    else:
        check(f"{name} at {t} s: exit 4 (interrupted)", rc == 4, f"exit {rc}")
        check("the file's status is 'interrupted'", st == "interrupted", st)
    n, m = counts(out)
    check(f"{name} at {t} s: {n} of {m} points in the file, some missing", 0 < n < m)
    r = subprocess.run(cmd + ["-o", out, "--resume"], capture_output=True, text=True)
    check(f"resume after {name}: exit {r.returncode}", r.returncode == 0, r.stderr.strip())
    same(ref, out)


def ranks(b, case, d, mpirun, sets):
    """The ranks attribute over resumes with other rank counts: it is the most ranks any
    run of the file had (the range of its rank variable), and the resumed points' rank
    values lie in the resuming run's range. A line is made incomplete by resetting its
    converged flags to the fill value, as a killed writer leaves them."""
    def run(n, out, resume):
        launch = [mpirun, "--oversubscribe", "--allow-run-as-root", "-n", str(n)] if n > 1 else []
        r = subprocess.run(launch + [b, "sweep", case, "--quiet", "-o", out] + sets
                           + (["--resume"] if resume else []), capture_output=True, text=True)
        check(f"{'resume' if resume else 'sweep'} on {n} rank(s): exit {r.returncode}",
              r.returncode == 0, r.stderr.strip())

    def drop_last_line(out):
        with netCDF4.Dataset(out, "a") as f:
            f.variables["converged"][-1, -1, :] = netCDF4.default_fillvals["i4"]

    def attrs(out):
        with netCDF4.Dataset(out) as f:
            f.set_auto_mask(False)
            return int(f.getncattr("ranks")), f.variables["rank"][:]

    ref, out = os.path.join(d, "ranks_ref.nc"), os.path.join(d, "ranks.nc")
    run(2, ref, False)
    run(2, out, False)
    for n, want in ((3, 3), (1, 3)):
        drop_last_line(out)
        run(n, out, True)
        got, rank = attrs(out)
        check(f"resumed on {n} rank(s): ranks attribute {got}, expected {want}", got == want)
        last = rank[-1, -1, :]
        check(f"resumed on {n} rank(s): the recomputed line's ranks {sorted(set(last.tolist()))} "
              f"within 0 .. {n - 1}", bool(((last >= 0) & (last < n)).all()))
    same(ref, out)


if __name__ == "__main__":
    args = sys.argv[1:]
    sets = args[args.index("--") + 1:] if "--" in args else []
    args = args[:args.index("--")] if "--" in args else args
    mode, b, case, d = args[:4]
    opts = args[4:]
    part = opts[opts.index("--part") + 1] if "--part" in opts else None
    mpirun = opts[opts.index("--mpi") + 1] if "--mpi" in opts else None
    os.makedirs(d, exist_ok=True)
    if mode == "kill":
        kill(b, case, d, part, mpirun, sets)
    elif mode == "term":
        term(b, case, d, sets, mpirun)
    elif mode == "ranks":
        ranks(b, case, d, mpirun, sets)
    elif mode == "status":
        status(b, case, d, sets, python="--no-python" not in opts)
    else:
        refuse(b, case, d, sets)
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
