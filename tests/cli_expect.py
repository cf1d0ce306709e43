#!/usr/bin/python3
"""Run a rollsim command line and check what a user sees: exit status, stdout, stderr, files.

Usage: cli_expect.py [--exit N] [--stdout RE]... [--no-stdout RE]... [--stderr RE]...
                     [--no-stderr RE]... [--quiet-stderr] [--out FILE]... [--absent FILE]...
                     -- COMMAND [ARG...]

Every --stdout/--stderr regular expression must match (re.search, multi-line), every --no-*
must not; --quiet-stderr: stderr must be empty (no warning for a plausible case). --out FILE is
removed first and must exist afterwards; --absent FILE is removed first and must not exist
afterwards (nothing half-written on invalid input).
"""
import argparse
import os
import re
import subprocess
import sys


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exit", type=int, default=0)
    for name in ("stdout", "no-stdout", "stderr", "no-stderr", "out", "absent"):
        p.add_argument(f"--{name}", action="append", default=[])
    p.add_argument("--quiet-stderr", action="store_true")
    p.add_argument("command", nargs=argparse.REMAINDER)
    a = p.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    for f in a.out + a.absent:
        if os.path.exists(f):
            os.remove(f)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    print("$", " ".join(cmd))
    print("--- stdout\n" + proc.stdout + "--- stderr\n" + proc.stderr + "---")
    fail = []
    if proc.returncode != a.exit:
        fail.append(f"exit status {proc.returncode}, expected {a.exit}")
    for pat in a.stdout:
        if not re.search(pat, proc.stdout, re.M):
            fail.append(f"stdout does not match {pat!r}")
    for pat in a.no_stdout:
        if re.search(pat, proc.stdout, re.M):
            fail.append(f"stdout matches {pat!r}")
    for pat in a.stderr:
        if not re.search(pat, proc.stderr, re.M):
            fail.append(f"stderr does not match {pat!r}")
    for pat in a.no_stderr:
        if re.search(pat, proc.stderr, re.M):
            fail.append(f"stderr matches {pat!r}")
    if a.quiet_stderr and proc.stderr:
        fail.append("stderr is not empty")
    for f in a.out:
        if not os.path.exists(f):
            fail.append(f"{f} was not written")
    for f in a.absent:
        if os.path.exists(f) or os.path.exists(f + ".part"):
            fail.append(f"{f} was written")
    for f in fail:
        print("FAIL:", f)
    print("OK" if not fail else f"{len(fail)} failed")
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main())
