#!/usr/bin/python3
"""Output problems: an output path that cannot be written, and a disk that fills up during
the run. Each must end with exit code 1 (internal/output error: not a crash, not 0) and a
message naming the output file and the reason; nothing outside the work directory is
touched, and what is left on disk is valid.

Usage:
  check_output_errors.py paths ROLLSIM CASE.yaml WORKDIR
      -o under /proc, under a regular file, onto a directory, a FIFO or a character device
      (the file is built as PATH.part and renamed over PATH: a device or pipe must not be
      replaced, as `-o /dev/null` as root would). Tests run as root, so permission bits
      would not stop anything: these paths fail for every user.
  check_output_errors.py diskfull ROLLSIM CASE.yaml WORKDIR
      a 64 KiB tmpfs fills up after some records (the file keeps them, complete), a 4 KiB
      one while the file is created (nothing left behind), a read-only one at once.
      Needs mount rights; exits with 77 (ctest: skipped) and says why when it has none.
CASE is cases/default.yaml.
"""
import os
import stat
import subprocess
import sys

import netCDF4

sys.dont_write_bytecode = True
from rs_check import (DT, MU, PIN, check_records, prepare_dir, run,  # noqa: E402
                      summary_records)

SKIPPED = 77
# From the steady state every record takes a few steps: 135 records in a fraction of a second.
FAST = ["--set", "simulation.initial_state=steady", "--quiet"] + PIN


def expect_output_error(rollsim, case, path, reason, cwd):
    """Run with -o path; exit code 1 and one message naming path and reason."""
    code, stdout, stderr = run(rollsim, ["run", case, "-o", path] + FAST, cwd=cwd)
    what = f"-o {path}"
    assert code == 1, f"{what}: exit code {code}, want 1\n{stderr}"
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, f"{what}: want one message, got:\n{stderr}"
    assert f"output file {path}" in lines[0], f"{what}: message does not name it: {lines[0]}"
    assert reason in lines[0], f"{what}: message does not say {reason!r}: {lines[0]}"
    print(f"ok: {what}: exit 1: {lines[0]}")
    return stdout, lines[0]


def check_paths(rollsim, case, workdir):
    out = prepare_dir(workdir)
    regular = os.path.join(out, "regular_file")
    with open(regular, "w") as f:
        f.write("not a directory\n")
    directory = os.path.join(out, "a_directory")
    os.mkdir(directory)
    fifo = os.path.join(out, "fifo")
    os.mkfifo(fifo)

    expect_output_error(rollsim, case, "/proc/rollsim_no_such_dir/out.nc", "cannot create", out)
    expect_output_error(rollsim, case, "/proc/out.nc", "cannot create", out)
    expect_output_error(rollsim, case, os.path.join(regular, "out.nc"), "Not a directory", out)
    expect_output_error(rollsim, case, os.path.join(regular, "sub", "out.nc"),
                        "Not a directory", out)
    expect_output_error(rollsim, case, directory, "not a regular file", out)
    assert os.path.isdir(directory) and not os.listdir(directory), f"{directory} changed"
    expect_output_error(rollsim, case, fifo, "not a regular file", out)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode), f"{fifo} was replaced"
    try:  # a copy of /dev/full (char 1,7); needs CAP_MKNOD
        device = os.path.join(out, "full")
        os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
    except OSError as e:
        print(f"note: cannot create a device node ({e}): device check skipped")
    else:
        expect_output_error(rollsim, case, device, "not a regular file", out)
        assert stat.S_ISCHR(os.lstat(device).st_mode), f"{device} was replaced"
    left = sorted(os.listdir(out))
    assert left == sorted(["regular_file", "a_directory", "fifo"] +
                          (["full"] if os.path.exists(os.path.join(out, "full")) else [])), \
        f"files left in {out}: {left}"


def mount_tmpfs(where, options):
    os.makedirs(where, exist_ok=True)
    p = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", where],
                       capture_output=True, text=True)
    return p.returncode == 0, p.stderr.strip()


def umount(where):
    subprocess.run(["umount", where], check=False)


def check_disk_full(rollsim, case, workdir):
    out = prepare_dir(workdir)
    mnt = os.path.join(out, "mnt")
    ok, why = mount_tmpfs(mnt, "size=64k")
    if not ok:
        print(f"SKIP: cannot mount a small tmpfs to fill up ({why or 'mount failed'}); "
              "disk-full checks not run")
        sys.exit(SKIPPED)
    try:
        # The header and x take the first blocks; records (2.5 KiB each) fill the rest.
        path = os.path.join(mnt, "full.nc")
        stdout, msg = expect_output_error(rollsim, case, path, "No space left on device", out)
        assert os.path.exists(path), f"{path}: the records written before the disk filled are gone"
        with netCDF4.Dataset(path) as ds:
            # the status says why, rewritten in place (the header's bytes exist already)
            assert ds.status.startswith("failed: ") and "No space left on device" in ds.status, \
                f"{path}: status {ds.status!r}"
            nrec = check_records(ds, DT, MU, path)
        assert nrec >= 2, f"{path}: {nrec} records, expected the disk to fill later"
        assert summary_records(stdout) == nrec, \
            f"the summary says {summary_records(stdout)} records, the file holds {nrec}"
        assert f"writing record {nrec} " in msg, f"the message names another record: {msg}"
        assert os.listdir(mnt) == ["full.nc"], f"left in {mnt}: {os.listdir(mnt)}"
        print(f"ok: disk full after {nrec} records: the file holds them, complete")
    finally:
        umount(mnt)

    try:  # a sweep's file (77 KB) is allocated at creation: no point computed, no file
        ok, why = mount_tmpfs(mnt, "size=64k")
        assert ok, why
        sweep_case = os.path.join(os.path.dirname(case), "creep_curves.yaml")
        path = os.path.join(mnt, "sweep.nc")
        p = subprocess.run([rollsim, "sweep", sweep_case, "-o", path, "--quiet"],
                           capture_output=True, text=True)
        assert p.returncode == 1 and "No space left on device" in p.stderr, \
            f"sweep on a full disk: exit {p.returncode}: {p.stderr}"
        assert "points solved" not in p.stdout, f"a summary without a file: {p.stdout}"
        assert not os.listdir(mnt), f"left in {mnt}: {os.listdir(mnt)}"
        print("ok: a sweep on a full disk: exit 1, nothing left")
    finally:
        umount(mnt)

    try:  # too small for the header (4 KiB reserve + case text + ...): nothing left behind
        ok, why = mount_tmpfs(mnt, "size=4k")
        assert ok, why
        path = os.path.join(mnt, "tiny.nc")
        expect_output_error(rollsim, case, path, "No space left on device", out)
        assert not os.listdir(mnt), f"left in {mnt}: {os.listdir(mnt)}"
    finally:
        umount(mnt)

    try:
        ok, why = mount_tmpfs(mnt, "size=64k,ro")
        assert ok, why
        expect_output_error(rollsim, case, os.path.join(mnt, "ro.nc"), "Read-only file system",
                            out)
    finally:
        umount(mnt)


def main():
    mode, rollsim, case, workdir = sys.argv[1:5]
    if mode == "paths":
        check_paths(rollsim, case, workdir)
    elif mode == "diskfull":
        check_disk_full(rollsim, case, workdir)
    else:
        sys.exit(f"unknown mode {mode}")


if __name__ == "__main__":
    main()
