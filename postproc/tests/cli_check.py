#!/usr/bin/python3
"""Run a command and check its exit status, stderr and output file.

Usage: cli_check.py [--exit N] [--stderr REGEX] [--out FILE [--min-bytes N] [--head TEXT]]
                    -- COMMAND [ARG...]

--out FILE is removed before the command runs, so a stale file from an earlier run cannot pass.
"""
import argparse
import os
import re
import subprocess
import sys


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exit", type=int, default=0, help="expected exit status")
    p.add_argument("--stderr", help="regular expression stderr must match (re.search)")
    p.add_argument("--out", help="file the command must write")
    p.add_argument("--min-bytes", type=int, default=1, help="minimum size of --out")
    p.add_argument("--head", help="text the first 4 KB of the file must contain (e.g. %%PDF, <svg)")
    p.add_argument("command", nargs=argparse.REMAINDER)
    a = p.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if a.out and os.path.exists(a.out):
        os.remove(a.out)
    proc = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    failures = []
    if proc.returncode != a.exit:
        failures.append(f"exit status {proc.returncode}, expected {a.exit}")
    if a.stderr and not re.search(a.stderr, proc.stderr):
        failures.append(f"stderr does not match {a.stderr!r}")
    if a.exit != 0 and proc.stderr.strip().count("\n") > 0 and a.stderr:
        # An error is one clear line (a matplotlib/font warning would be a second line).
        failures.append("stderr has more than one line")
    if a.out:
        if not os.path.exists(a.out):
            failures.append(f"{a.out} was not written")
        else:
            size = os.path.getsize(a.out)
            print(f"{a.out}: {size} bytes (minimum {a.min_bytes})")
            if size < a.min_bytes:
                failures.append(f"{a.out}: {size} bytes < {a.min_bytes}")
            if a.head:
                with open(a.out, "rb") as f:
                    head = f.read(4096)
                if a.head.encode() not in head:
                    failures.append(f"{a.out}: first 4 KB do not contain {a.head!r}")
    for f in failures:
        print(f"FAIL: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
