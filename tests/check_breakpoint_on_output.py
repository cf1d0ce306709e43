"""A history breakpoint on the output grid up to rounding (ctest, /usr/bin/python3).

A creepage step at t = 2e-5 s with output_interval = 2e-7 s: the 100th output time is
100 * 2e-7 = 1.9999999999999998e-05, an ulp before the breakpoint. The run used to fail
there with IDA_ILL_INPUT (asked for the output time while IDA's stop time was the
breakpoint). Checks: exit 0, status complete, all 501 records, the creepage -2e-4 before
the step and -4e-4 after it.

usage: check_breakpoint_on_output.py ROLLSIM CASE.yaml OUT.nc
"""
import subprocess
import sys

import netCDF4

rollsim, case, out = sys.argv[1:4]
cmd = [rollsim, "run", case, "--set", "simulation.mode=transient",
       "--set", "simulation.initial_state=steady",
       "--set", "rolling.creepage={steps: [[0.0, -2.0e-4], [2.0e-5, -4.0e-4]]}",
       "--set", "simulation.end_time=1.0e-4", "--set", "simulation.output_interval=2.0e-7",
       "-o", out, "--quiet"]
rc = subprocess.run(cmd).returncode
failures = 0


def check(what, ok, detail=""):
    global failures
    print(("ok  " if ok else "FAIL"), what, detail)
    failures += not ok


check("exit 0", rc == 0, "got %d" % rc)
ds = netCDF4.Dataset(out)
check("status complete", ds.status == "complete", ds.status)
n = len(ds["time"])
check("501 records", n == 501, "got %d" % n)
xi = ds["creepage"][:]
check("creepage -2e-4 before the step (record 99)", n > 101 and abs(xi[99] + 2e-4) < 1e-15)
check("creepage -4e-4 after the step (record 101)", n > 101 and abs(xi[101] + 4e-4) < 1e-15)
sys.exit(1 if failures else 0)
