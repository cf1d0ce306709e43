"""End-to-end checks on netCDF files written by `rollsim run` (ctest, /usr/bin/python3).

transient_vs_steady TRANSIENT.nc STEADY.nc
    The default case (Carter, rolled 20 contact lengths from rest) ends within
    1e-4 of the steady solution of the same grid (docs/verification.md 3).
final_matches RUN.nc STEADY.nc TOL
    A transient run at constant final inputs ends at the steady solution of the same grid.
carter STEADY.nc MU XI
    Steady F_x/(mu F_n) against Carter's 1 - (1 - |xi| R/(mu a))^2 (R = 500 mm,
    a = 1.000 mm): the first-order scheme is within 1 % at dx = a/47.6
    (tests/test_carter_steady.c shows the linear convergence).
sine RUN.nc MEAN AMPLITUDE FREQUENCY
    A run with a sine creepage history (cases/sine_creepage.yaml, started from steady
    rolling): the stored creepage is the prescribed sine at every record (to 1e-15); the
    force stays below the friction limit mu F_n; after the first period (30 contact
    lengths rolled, beyond the ~18 a start-up needs to come within 1e-4 of its end state)
    the force is periodic: the last period repeats the one before to 1e-4 of its
    peak-to-peak amplitude, or to 4 rtol max |F_x| (rtol the run's solver_rtol) where that is
    looser: each period is integrated on its own sequence of steps, and each lies within about
    2 rtol max |F_x| of the exact response (measured 2.4e-3 of max |F_x| at rtol 1.26e-3 against
    an rtol 1e-9 run), so two periods differ by at most twice that; and its strongest non-constant harmonic is the creepage's
    frequency (the response is not linear in partial slip, so higher harmonics exist,
    but weaker).
"""
import math
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


def sine(path, mean, amplitude, frequency):
    import numpy as np
    import yaml

    d = open_complete(path)
    mu = float(yaml.safe_load(d.getncattr("case"))["friction"]["mu"])
    t = np.asarray(d["time"][:], dtype=float)
    fx = np.asarray(d["Fx"][:], dtype=float)
    fn = np.asarray(d["Fn"][:], dtype=float)
    xi = np.asarray(d["creepage"][:], dtype=float)
    want = mean + amplitude * np.sin(2.0 * math.pi * frequency * t)
    check("max |stored creepage - prescribed sine|", float(np.max(np.abs(xi - want))), 0.0, 1e-15)
    ratio = float(np.max(np.abs(fx) / (mu * fn)))
    print(("ok  " if ratio < 1.0 else "FAIL"), f"max |F_x| / (mu F_n) = {ratio:.6f} < 1 (friction limit)")
    if not ratio < 1.0:
        sys.exit(1)
    period = 1.0 / frequency
    dt = t[1] - t[0]
    k = int(round(period / dt))
    check("records per period (whole)", k * dt, period, 1e-9 * period)
    if len(t) < 2 * k + 1:
        fail("fewer than two periods stored")
    last, before = fx[-k - 1:], fx[-2 * k - 1:-k]
    span = float(np.ptp(fx[-2 * k - 1:]))
    rtol = float(d.getncattr("solver_rtol"))
    tol = max(1e-4, 4.0 * rtol * float(np.max(np.abs(fx))) / span)
    check("last period vs the one before, max |difference| / peak-to-peak",
          float(np.max(np.abs(last - before))) / span, 0.0, tol)
    seg = fx[-2 * k:]
    spectrum = np.abs(np.fft.rfft(seg - seg.mean()))
    peak = int(np.argmax(spectrum))
    check("strongest harmonic of F_x over the last two periods (Hz)", peak / (2 * period),
          frequency, 0.0)


if __name__ == "__main__":
    cmd = sys.argv[1]
    if cmd == "transient_vs_steady":
        transient_vs_steady(sys.argv[2], sys.argv[3])
    elif cmd == "final_matches":
        final_matches(sys.argv[2], sys.argv[3], float(sys.argv[4]))
    elif cmd == "carter":
        carter(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
    elif cmd == "sine":
        sine(sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]))
    else:
        fail(f"unknown check {cmd}")
