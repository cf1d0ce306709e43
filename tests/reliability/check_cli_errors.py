#!/usr/bin/python3
"""Invalid input through the command line (exit codes: README): exit code 2,
one message, nothing run, no output file.

Usage:
  check_cli_errors.py badfile ROLLSIM FILE.yaml WORKDIR
      `rollsim run FILE -o WORKDIR/x.nc` and `rollsim check FILE` both exit with 2 and print
      one line on stderr that starts with "FILE:LINE: " and contains every "# expect:" text
      of the file's header (the same header tests/test_case_bad.c reads; without "# line:"
      any line number); nothing on stdout; WORKDIR stays empty.
  check_cli_errors.py cmdline ROLLSIM CASE.yaml WORKDIR
      bad command lines (unknown option, missing case, --set without '=', unknown --set
      key, ...) exit with 2, say what is wrong, and create nothing.
"""
import os
import re
import sys

sys.dont_write_bytecode = True
from rs_check import prepare_dir, run  # noqa: E402


def header(path):
    expect, line = [], None
    with open(path, "rb") as f:
        for raw in f:
            if not raw.startswith(b"#"):
                break
            text = raw.decode("utf-8", "replace").rstrip("\r\n")
            if text.startswith("# expect: "):
                expect.append(text[len("# expect: "):])
            elif text.startswith("# line: "):
                line = int(text[len("# line: "):])
    assert expect, f"{path}: no '# expect:' header"
    return expect, line


def check_bad_file(rollsim, path, workdir):
    expect, line = header(path)
    out = prepare_dir(workdir)
    prefix = re.escape(path) + (f":{line}: " if line else r":\d+: ")
    for args in (["run", path, "-o", os.path.join(out, "x.nc"), "--quiet"], ["check", path]):
        what = "rollsim " + " ".join(args)
        code, stdout, stderr = run(rollsim, args, cwd=out)
        assert code == 2, f"{what}: exit code {code}, want 2\n{stderr}"
        lines = [s for s in stderr.splitlines() if s.strip()]
        assert len(lines) == 1, f"{what}: want one message on stderr, got {len(lines)}:\n{stderr}"
        msg = lines[0]
        assert re.match(prefix, msg), f"{what}: message does not start with {prefix!r}: {msg}"
        for text in expect:
            assert text in msg, f"{what}: message does not contain {text!r}: {msg}"
        assert stdout == "", f"{what}: printed on stdout:\n{stdout}"
        left = os.listdir(out)
        assert not left, f"{what}: created {left}"
    print(f"ok: {os.path.basename(path)}: {msg}")


def check_command_lines(rollsim, case, workdir):
    out = prepare_dir(workdir)
    nc = os.path.join(out, "x.nc")
    # (arguments, regular expression the message must match)
    bad = [
        ([], r"usage: rollsim run"),
        (["frobnicate", case], r"unknown command 'frobnicate'"),
        (["run"], r"missing CASE\.yaml"),
        (["run", "-o", nc], r"missing CASE\.yaml"),
        (["run", "--quiet", "--set", "grid.cells=50"], r"missing CASE\.yaml"),
        (["check"], r"missing CASE\.yaml"),
        (["run", case, "--bogus", "-o", nc], r"unknown option '--bogus'"),
        (["run", "--frobnicate", case, "-o", nc], r"unknown option '--frobnicate'"),
        (["check", case, "-x"], r"unknown option '-x'"),
        (["run", case, "-o"], r"-o needs a file name"),
        (["run", case, "-o", nc, "--set"], r"--set needs KEY=VALUE"),
        (["run", case, "-o", nc, "--set", "grid.cells"], r"grid\.cells: expected KEY=VALUE"),
        (["check", case, "--set", "friction.mu"], r"friction\.mu: expected KEY=VALUE"),
        (["run", case, "-o", nc, "--set=grid.cells"], r"grid\.cells: expected KEY=VALUE"),
        (["run", case, "-o", nc, "--set", "=3"], r"=3"),
        (["run", case, "-o", nc, "--set", "grid.cellz=50"], r"grid\.cellz: unknown key"),
        (["check", case, "--set", "grid.cellz=50"], r"grid\.cellz: unknown key"),
        (["run", case, "-o", nc, "--set", "nosuch.key=1"], r"nosuch.*unknown key"),
        (["run", case, "-o", nc, "--set", "grid.cells=abc"], r"grid\.cells: expected a number"),
        (["run", case, "-o", nc, "--set", "friction.mu=-1"], r"friction\.mu"),
        (["run", case, "-o", nc, "--set", "grid.cells.x=3"], r"grid\.cells"),
        (["run", case, case, "-o", nc], r"more than one case file"),
        (["run", os.path.join(out, "no_such_case.yaml"), "-o", nc], r"no_such_case\.yaml"),
        (["run", out, "-o", nc], re.escape(out)),
    ]
    for args, pattern in bad:
        what = "rollsim " + " ".join(args)
        code, stdout, stderr = run(rollsim, args, cwd=out)
        assert code == 2, f"{what}: exit code {code}, want 2\n{stderr}"
        assert re.search(pattern, stderr), f"{what}: stderr does not match {pattern!r}:\n{stderr}"
        assert "records" not in stdout, f"{what}: something was run:\n{stdout}"
        left = os.listdir(out)
        assert not left, f"{what}: created {left}"
        print(f"ok: {what} -> 2: {stderr.splitlines()[0]}")


def main():
    mode, rollsim, target, workdir = sys.argv[1:5]
    if mode == "badfile":
        check_bad_file(rollsim, target, workdir)
    elif mode == "cmdline":
        check_command_lines(rollsim, target, workdir)
    else:
        sys.exit(f"unknown mode {mode}")


if __name__ == "__main__":
    main()
