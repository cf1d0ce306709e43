"""End-to-end checks on netCDF files written by `rollsim run` (ctest, /usr/bin/python3).

transient_vs_steady TRANSIENT.nc STEADY.nc
    The default case (Carter, rolled 20 contact lengths from rest) ends within
    1e-4 of the steady solution of the same grid (verification.md §3).
final_matches RUN.nc STEADY.nc TOL
    A transient run at constant final inputs ends at the steady solution of the same grid.
carter STEADY.nc MU XI
    Steady F_x/(mu F_n) against Carter's 1 - (1 - |xi| R/(mu a))^2 (R = 500 mm,
    a = 1.000 mm): the first-order scheme is within 1 % at dx = a/47.6
    (tests/test_carter_steady.c shows the linear convergence).
"""
import sys

import netCDF4


def fail(msg):
    print("FAIL", msg)
    sys.exit(1)


def check(what, got, want, tol):
    ok = abs(got - want) <= tol
    print(("ok  " if ok else "FAIL"), f"{what}: got {got:.10g}, want {want:.10g}, tol {tol:.3g}")
    if not ok:
        sys.exit(1)


def open_complete(path):
    ds = netCDF4.Dataset(path)
    status = ds.getncattr("status")
    if status != "complete":
        fail(f"{path}: status {status!r}")
    return ds


def transient_vs_steady(tpath, spath):
    t = open_complete(tpath)
    s = open_complete(spath)
    fx_t = float(t["Fx"][-1])
    fx_s = float(s["Fx"][-1])
    check("records of the default case (40 mm at 0.3 mm per record, plus t = 0)",
          len(t["time"]), 135, 0)
    check("time of the last record = rolled distance / V (s)", float(t["time"][-1]), 40.0 / 30000.0, 1e-15)
    check("transient F_x relative to steady F_x", fx_t / fx_s, 1.0, 1e-4)
    # The force builds up from zero: the first record is at rest.
    check("F_x at t = 0 (rest)", float(t["Fx"][0]), 0.0, 0.0)


def carter(path, mu, xi):
    s = open_complete(path)
    ratio = float(s["Fx"][-1]) / (mu * float(s["Fn"][-1]))
    a, R = 1.0, 500.0
    aprime = 1.0 - abs(xi) * R / (mu * a)
    want = 1.0 - aprime ** 2
    check(f"steady F_x/(mu F_n) at mu = {mu}, xi = {xi} vs Carter", ratio, want, 0.01 * want)


def final_matches(tpath, spath, tol):
    t = open_complete(tpath)
    s = open_complete(spath)
    check(f"{tpath}: final F_x relative to the steady F_x of {spath}",
          float(t["Fx"][-1]) / float(s["Fx"][-1]), 1.0, tol)


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "transient_vs_steady":
        transient_vs_steady(sys.argv[2], sys.argv[3])
    elif cmd == "final_matches":
        final_matches(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    elif cmd == "carter":
        carter(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    else:
        fail(f"unknown check {cmd}")
