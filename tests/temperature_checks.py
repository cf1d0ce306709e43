"""Shared by the temperature checks (check_temperature, check_heat_memory): the pass/fail line
with what was got and wanted, and a rollsim run that must succeed."""
import subprocess
import sys

import netCDF4


class Checks:
    """check(ok, what, got, want) prints one line; failures counts the failed ones."""

    def __init__(self):
        self.failures = 0

    def __call__(self, ok, what, got, want):
        print(f"{'ok  ' if ok else 'FAIL'} {what}: got {got!r}, want {want!r}")
        self.failures += not ok


def run(rollsim, args, out):
    """The netCDF file of `rollsim ARGS -o OUT --quiet`; exits the check if the run fails."""
    cmd = [rollsim] + args + ["-o", out, "--quiet"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print("FAIL", " ".join(cmd), r.stdout, r.stderr)
        sys.exit(1)
    return netCDF4.Dataset(out)
