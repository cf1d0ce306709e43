#!/usr/bin/python3
"""The README's Python example: creep-force curves for three friction coefficients from a
case given as a dict, in-process through librollsim. Run from the repository root after the
README's build:  PYTHONPATH=postproc /usr/bin/python3 docs/python_example.py
Writes docs/figures/python_creep_curves.png."""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rollsim

case = {
    "title": "Carter's problem with local plasticity",
    "contact": {"normal_load": 1323.6, "radius": 11.75},
    "grid": {"cells": 100},
    "material": {"shear_modulus": 77519.4, "poisson_ratio": 0.29},
    "friction": {"mu": 0.3},
    "plasticity": {"tau_c0": 200.0, "k_rel": 0.3},
    "rolling": {"velocity": 30000.0, "creepage": 0.0},
    "simulation": {"mode": "steady"},
    "output": {"fields": []},
    "sweep": {"friction.mu": [0.2, 0.3, 0.4],
              "rolling.creepage": {"linspace": [0.0, -0.04, 41]}},
}
print(rollsim.check(case)["hertz.half_width"], "mm Hertz half-width")
sw = rollsim.sweep(case)                                    # an xarray.Dataset
elastic = rollsim.sweep(case, set={"plasticity": None})      # the same without plasticity
fig, ax = plt.subplots(figsize=(6, 4))
for mu in sw.friction_mu.values:
    line, = ax.plot(-100 * sw.rolling_creepage, sw.traction_coefficient.sel(friction_mu=mu),
                    label=f"mu = {mu:g}, plastic")
    ax.plot(-100 * elastic.rolling_creepage, elastic.traction_coefficient.sel(friction_mu=mu),
            "--", color=line.get_color(), label=f"mu = {mu:g}, elastic")
ax.set_xlabel("-creepage [%]")
ax.set_ylabel("F_x / F_n")
ax.set_title("rollsim.sweep: tau_c0 = 200 N/mm^2, k_rel = 0.3, 100 cells", fontsize=10)
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig("docs/figures/python_creep_curves.png", dpi=90)
