#!/usr/bin/python3
"""rollsim run with a moving wheelset (profiles.lateral_displacement a history; the geometry
updated at the start of every output interval, docs/model.md §20 "A moving wheelset") and its
file (docs/file-format.md "Wheel-rail sweep files", over time):

1. held positions: lateral displacement in steps 0, 2, 7.5 mm (tread, tread, flange) held over
   three intervals of 100 mm rolled each (20 contact lengths): each record is the steady state of
   its position, against `rollsim sweep` at the same positions (an independent path: the steady
   solver): F_n and the contact angle identical (the same geometry) to 1e-9, F_x and F_s within
   3e-3 mu F_n (the transient's time tolerance, solver.rtol auto 3e-3 in 3D; after 20 contact
   lengths the start-up has decayed);
2. a ramp (0 -> 1 mm over 0.5 s: the wheelset moves toward the rail at 2 mm/s): the file's
   lateral creepage of each patch is the closed form with the lateral velocity,
   eta = (v_y - omega r sin psi) cos(delta) / V with v_y = -2 mm/s (toward the track centre),
   xi = 1 - omega r cos(psi) / V, to 1e-12; and the lateral force on the wheel points toward the
   track centre (it resists the wheelset's motion toward the rail): F_s > 0 at every record;
3. the state carried from interval to interval: a ramp of 1e-5 mm over 30 mm rolled (lateral
   speed 6.7e-4 mm/s, eta 3e-7) in intervals of 1 mm rolled, a fifth of the contact's length: the
   last record is the steady state of the position to 3e-3 mu F_n, while a patch started from
   rest in every interval would show the start-up's first millimetre (F_x about 0.1 of steady).

Usage: check_wr_moving.py ROLLSIM CASE OUTDIR
"""
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np

rollsim, case, outdir = sys.argv[1:4]
os.makedirs(outdir, exist_ok=True)
failures = 0
mu, V = 0.3, 2000.0


def check(ok, what):
    global failures
    failures += not ok
    print(("ok   " if ok else "FAIL ") + what)


def read(path):
    with netCDF4.Dataset(path) as nc:
        return {k: np.ma.filled(nc.variables[k][:].astype(float), np.nan) for k in nc.variables}, \
            nc.getncattr("status")


def run(name, *args):
    out = os.path.join(outdir, name + ".nc")
    if os.path.exists(out):
        os.remove(out)
    subprocess.run([rollsim, *args, "-o", out, "--quiet"], check=True, capture_output=True)
    return read(out)


held, st = run("held", "run", case, "--set", "simulation.mode=transient",
               "--set", "simulation.end_time=0.15", "--set", "simulation.output_interval=0.05",
               "--set", "profiles.lateral_displacement={steps: [[0, 0], [0.05, 2], [0.1, 7.5]]}")
steady, _ = run("steady", "sweep", case, "--set", "sweep.profiles.lateral_displacement=[0, 2, 7.5]")
check(st == "complete" and len(held["time"]) == 3,
      f"held positions: status {st!r}, {len(held['time'])} records")
for i in range(3):
    fn, d = held["Fn"][i, 0], held["contact_angle"][i, 0]
    check(abs(fn - steady["Fn"][i, 0]) <= 1e-9 * fn and abs(d - steady["contact_angle"][i, 0]) <= 1e-12,
          f"{held['lateral_displacement'][i]:g} mm: F_n {fn:.9g} N, angle {math.degrees(d):.4f} deg as the sweep's")
    for name in ("Fx", "Fs"):
        diff = abs(held[name][i, 0] - steady[name][i, 0]) / (mu * fn)
        check(diff <= 3e-3, f"{held['lateral_displacement'][i]:g} mm: {name} {held[name][i, 0]:.6g} "
              f"against steady {steady[name][i, 0]:.6g} ({diff:.2g} mu F_n)")

ramp, st = run("ramp", "run", case, "--set", "simulation.mode=transient",
               "--set", "simulation.end_time=0.5", "--set", "simulation.output_interval=0.05",
               "--set", "profiles.lateral_displacement={ramp: {from: 0, to: 1, start: 0, duration: 0.5}}")
check(st == "complete" and len(ramp["time"]) == 10, f"ramp: status {st!r}, {len(ramp['time'])} records")
worst = 0.0
for i in range(len(ramp["time"])):
    psi, om = ramp["yaw"][i], ramp["wheel_angular_velocity"][i]
    for k in range(int(ramp["patches"][i])):
        r, d = ramp["rolling_radius"][i, k], ramp["contact_angle"][i, k]
        if not math.isfinite(ramp["Fn"][i, k]) or ramp["Fn"][i, k] <= 0:
            continue
        eta = (-2.0 - om * r * math.sin(psi)) * math.cos(d) / V
        xi = 1 - om * r * math.cos(psi) / V
        worst = max(worst, abs(ramp["eta"][i, k] - eta), abs(ramp["xi"][i, k] - xi))
check(worst <= 1e-12, f"ramp: creepages against the closed forms with v_y = -2 mm/s (largest |diff| {worst:.2g})")
check(bool(np.all(ramp["Fs"][:, 0] > 0)), f"ramp: F_s > 0 at every record (smallest {np.min(ramp['Fs'][:, 0]):.1f} N)")

carry, st = run("carry", "run", case, "--set", "simulation.mode=transient",
                "--set", "simulation.rolled_distance=30", "--set", "simulation.output_interval=5e-4",
                "--set", "profiles.lateral_displacement={ramp: {from: 0, to: 1e-5, start: 0, duration: 0.015}}")
for name in ("Fx", "Fs"):
    diff = abs(carry[name][-1, 0] - steady[name][0, 0]) / (mu * carry["Fn"][-1, 0])
    check(st == "complete" and diff <= 3e-3,
          f"carried state: {name} after 30 mm in {len(carry['time'])} intervals {carry[name][-1, 0]:.6g} "
          f"against steady {steady[name][0, 0]:.6g} ({diff:.2g} mu F_n)")
check(abs(carry["Fx"][0, 0]) < 0.2 * abs(steady["Fx"][0, 0]),
      f"carried state: the first millimetre's F_x {carry['Fx'][0, 0]:.4g} N (a start-up from rest)")
sys.exit(1 if failures else 0)
