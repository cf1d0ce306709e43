#!/usr/bin/env python3
"""Surface temperature through the whole program (docs/model.md §18, docs/verification.md 26).

  check_temperature.py ROLLSIM CASES_DIR OUT_DIR

1. Energy, per record: the heat into both bodies, heat_input_1 + heat_input_2, equals the heat
   generated, 1e-3 (frictional_power + beta_pl plastic_power) (N mm/s -> W), to 1e-10 relative:
   q1 + q2 = q holds cell by cell and the per-cell sources are the terms of the reported powers.
   Checked in 2D steady rolling with plasticity (beta_pl = 0.7), in every record of a 2D
   transient with plasticity, and in 3D steady rolling with creepage, lateral creepage and spin.
2. Symmetry: equal bodies at equal bulk temperatures share the heat equally (q1 = q2 in every
   cell), heat_input_1 = heat_input_2 to 1e-12 relative, and T1 = T2 everywhere.
3. Cold meets hot without heat (creepage 0: no traction, no slip): body 1 at 0 degC, body 2 at
   150 degC with four times body 1's beta (sixteen times its conductivity): the contact
   temperature is (beta_1 T_1 + beta_2 T_2)/(beta_1 + beta_2) = 120 degC in every contact cell
   (two half-spaces brought into perfect contact hold that temperature for all time), to 1e-9
   degC; ahead of the contact both surfaces are at their bulk temperatures exactly.
4. Steady = transient limit: a transient started from steady rolling at constant inputs keeps
   the steady temperatures in every record after the start (its state stays the steady one to
   the integration tolerance): T_max within 1e-6 of the temperature rise of the steady run. The
   record at t = 0 is left out: its rates are the consistent rates of the start, which split the
   rate of cells at both bounds between slip and plastic flow otherwise than the steady solve
   (each power differs by a few 1e-4 there; from the first step on the rates are the
   integrator's).
5. A sweep's per-point T_max equals that of a separate steady run of each point to 1e-6 of the
   rise (the sweep continues from point to point, the run starts afresh: two paths to the same
   steady state, to the Newton tolerance); the sweep run in two parts and merged holds the same
   T_max and heat inputs bit for bit.
6. Without a temperature: block the files hold no temperature variable.
7. Restart with --append continues the temperature variables record by record; a file and a case
   that differ in having a temperature: block are refused (exit 2, the message names T1 and the
   block) before anything is written.
8. Post-processing: the creep-curve figure of a sweep with temperature draws each series' T_max
   (its --data rows) as the file holds them, point by point; the map figure draws T1.
"""
import os
import subprocess
import sys

import csv

import netCDF4
import numpy as np

from temperature_checks import Checks, run

POST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "postproc", "rollsim_post.py")

check = Checks()


def energy(d, frac, what):
    heat = d["heat_input_1"][:] + d["heat_input_2"][:]
    gen = 1e-3 * (d["frictional_power"][:] + frac * d["plastic_power"][:])
    rel = np.max(np.abs(heat - gen) / np.abs(gen))
    check(rel <= 1e-10 and len(heat) >= 1, f"{what}: heat into both bodies = generated heat "
          f"({len(heat)} records, {float(gen[-1]):.6g} W)", float(rel), "<= 1e-10")


def main():
    rollsim, cases, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    plast = os.path.join(cases, "carter_plast.yaml")
    temp = ["--set", "temperature={bulk: [20, 20], plastic_heat_fraction: 0.7}"]

    d = run(rollsim, ["run", plast] + temp, os.path.join(out, "steady2d.nc"))
    energy(d, 0.7, "2D steady, plastic")
    h1, h2 = float(d["heat_input_1"][-1]), float(d["heat_input_2"][-1])
    check(abs(h1 - h2) <= 1e-12 * abs(h1), "equal bodies: heat_input_1 = heat_input_2", h1, h2)
    T1, T2 = d["T1"][-1], d["T2"][-1]
    check(np.max(np.abs(T1 - T2)) <= 1e-12 * np.max(T1), "equal bodies: T1 = T2 everywhere",
          float(np.max(np.abs(T1 - T2))), 0.0)
    rise_steady = float(d["T_max"][-1]) - 20.0
    check(rise_steady > 0.0, "frictional and plastic heat warm the contact", rise_steady, "> 0")

    dt = run(rollsim, ["run", plast] + temp +
             ["--set", "simulation.mode=transient", "--set", "simulation.rolled_distance=3",
              "--set", "simulation.output_interval=2e-5"], os.path.join(out, "transient2d.nc"))
    energy(dt, 0.7, "2D transient from rest, plastic")

    ds = run(rollsim, ["run", plast] + temp +
             ["--set", "simulation.mode=transient", "--set", "simulation.initial_state=steady",
              "--set", "simulation.rolled_distance=3", "--set", "simulation.output_interval=2e-5"],
             os.path.join(out, "from_steady2d.nc"))
    dev = float(np.max(np.abs(ds["T_max"][1:] - 20.0 - rise_steady))) / rise_steady
    check(dev <= 1e-6, f"transient from steady keeps the steady T_max ({len(ds['time']) - 1} "
          "records after the start)", dev, "<= 1e-6 of the rise")

    d3 = run(rollsim, ["run", os.path.join(cases, "hertz3d_creep.yaml"), "--set",
                       "simulation.mode=steady", "--set", "grid.cells=[24, 24]",
                       "--set", "rolling.lateral_creepage=0.0005", "--set", "rolling.spin=0.0005",
                       "--set", "rolling.creepage=-0.001", "--set", "output.fields=[pn]",
                       "--set", "temperature={bulk: [20, 40], conductivity: [0.05, 0.03]}"],
             os.path.join(out, "steady3d.nc"))
    energy(d3, 1.0, "3D steady with spin")
    check(d3["T1"].dimensions == ("time", "y", "x"), "3D: T1 over (time, y, x)",
          d3["T1"].dimensions, ("time", "y", "x"))

    dc = run(rollsim, ["run", plast, "--set", "rolling.creepage=0", "--set",
                       "temperature={bulk: [0, 150], conductivity: [0.05, 0.8]}"],
             os.path.join(out, "cold_hot.nc"))
    pn = dc["pn"][-1]
    inside = pn > 0
    T1, T2 = dc["T1"][-1], dc["T2"][-1]
    dev = float(max(np.max(np.abs(T1[inside] - 120.0)), np.max(np.abs(T2[inside] - 120.0))))
    check(dev <= 1e-9, f"cold meets hot: T = (b1 T1 + b2 T2)/(b1 + b2) in {int(inside.sum())} "
          "contact cells (degC)", dev, "<= 1e-9")
    ahead = np.arange(len(pn)) > np.max(np.nonzero(inside)[0])
    check(np.all(T1[ahead] == 0.0) and np.all(T2[ahead] == 150.0),
          f"ahead of the contact ({int(ahead.sum())} cells) the bulk temperatures", "", "")

    sw = run(rollsim, ["sweep", plast] + temp, os.path.join(out, "sweep.nc"))
    k_rel = sw["plasticity_k_rel"][:]
    for i, k in enumerate(k_rel):
        dp = run(rollsim, ["run", plast] + temp + ["--set", f"plasticity.k_rel={float(k)!r}"],
                 os.path.join(out, f"point{i}.nc"))
        a, b = float(sw["T_max"][i]), float(dp["T_max"][-1])
        check(abs(a - b) <= 1e-6 * (b - 20.0), f"sweep point k_rel = {float(k):g}: T_max as a run",
              a, b)
        dp.close()

    cc = os.path.join(out, "creep.nc")
    run(rollsim, ["sweep", plast] + temp + ["--set", "sweep.plasticity.k_rel=[0.6, 0]", "--set",
                                             "sweep.rolling.creepage={linspace: [0, -0.002, 5]}"],
        cc).close()
    data = os.path.join(out, "creep.csv")
    subprocess.run([sys.executable, POST, "creepcurve", cc, "-o", os.path.join(out, "creep.png"),
                    "--data", data], check=True, capture_output=True)
    with netCDF4.Dataset(cc) as d:
        t_file = {(float(k), float(x)): float(d["T_max"][i, j])
                  for i, k in enumerate(d["plasticity_k_rel"][:])
                  for j, x in enumerate(d["rolling_creepage"][:])}
    rows = [r for r in csv.DictReader(open(data)) if r["quantity"] == "T_max"]
    worst = max(abs(float(r["y"]) - t_file[(float(r["plasticity.k_rel"]), float(r["x"]))])
                for r in rows)
    check(len(rows) == len(t_file) and worst <= 1e-12,
          f"creep-curve figure draws T_max as stored ({len(rows)} points)", worst, 0.0)
    r = subprocess.run([sys.executable, POST, "map", os.path.join(out, "steady3d.nc"), "--field",
                        "T1", "-o", os.path.join(out, "T1.png")], capture_output=True, text=True)
    check(r.returncode == 0, "map --field T1 of a 3D file", r.returncode, 0)

    parts = []
    for k in (1, 2):
        parts.append(os.path.join(out, f"part{k}.nc"))
        run(rollsim, ["sweep", plast] + temp + ["--part", f"{k}/2"], parts[-1]).close()
    merged = os.path.join(out, "merged.nc")
    subprocess.run([rollsim, "merge", merged] + parts, check=True, capture_output=True)
    with netCDF4.Dataset(merged) as dm:
        same = all(np.array_equal(dm[v][:], sw[v][:]) for v in
                   ("T_max", "heat_input_1", "heat_input_2"))
    check(same, "parts merged: T_max, heat inputs as the whole sweep", same, True)

    default = os.path.join(cases, "default.yaml")
    app = os.path.join(out, "append.nc")
    run(rollsim, ["run", default] + temp + ["--set", "simulation.rolled_distance=3"], app).close()
    r = subprocess.run([rollsim, "run", default] + temp + ["--set", "simulation.rolled_distance=6",
                        "--restart", app, "--append", "--quiet"], capture_output=True, text=True)
    with netCDF4.Dataset(app) as d:
        n = len(d["time"])
        ok = r.returncode == 0 and d["T1"].shape[0] == n and d["T_max"].shape[0] == n and \
            not np.any(np.isnan(d["T_max"][1:]))
    check(ok, f"--append continues T1, T_max ({n} records)", r.returncode, 0)
    size = os.path.getsize(app)
    r = subprocess.run([rollsim, "run", default, "--set", "simulation.rolled_distance=9",
                        "--restart", app, "--append", "--quiet"], capture_output=True, text=True)
    check(r.returncode == 2 and "T1" in r.stderr and "temperature: block" in r.stderr and
          os.path.getsize(app) == size, "--append without the block into a file with it: refused",
          (r.returncode, r.stderr.strip()), 2)

    dn = run(rollsim, ["run", plast], os.path.join(out, "none.nc"))
    names = [v for v in ("T1", "T2", "T_max", "heat_input_1", "heat_input_2") if v in dn.variables]
    check(not names, "no temperature: block, no temperature variables", names, [])

    print(f"{'passed' if not check.failures else 'FAILED'}: {check.failures} failure(s)")
    return 1 if check.failures else 0


if __name__ == "__main__":
    sys.exit(main())
