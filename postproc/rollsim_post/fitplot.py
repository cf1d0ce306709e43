"""rollsim fit's FIT.nc: measured points with the simulated curve, residuals below, the fitted
values with their standard errors in the legend (`rollsim_post.py fit FIT.nc -o fig.png`)."""
import os

import numpy as np

from . import PostError


def read_fit(path):
    """The fit file's parameters and points (PostError naming the file or variable)."""
    import netCDF4
    if not os.path.exists(path):
        raise PostError(f"{path}: no such file")
    try:
        ds = netCDF4.Dataset(path)
    except OSError as e:
        raise PostError(f"{path}: not a netCDF file ({e})") from None
    with ds:
        for v in ("parameter_name", "fitted", "standard_error", "measured", "simulated"):
            if v not in ds.variables:
                raise PostError(f"{path}: no variable '{v}': not a rollsim fit file")
        ds.set_auto_mask(False)
        names = ["".join(c.decode() for c in row if c not in (b"", b"\x00"))
                 for row in ds["parameter_name"][:]]
        inputs = [v for v in ds.variables.values()
                  if getattr(v, "role", None) == "input" and v.dimensions == ("point",)]
        if not inputs:
            raise PostError(f"{path}: no input column (a variable with role = input)")
        x = inputs[-1]
        units = ds["fitted"].getncattr("parameter_units").split(", ") \
            if "parameter_units" in ds["fitted"].ncattrs() else [""] * len(names)
        return {
            "title": getattr(ds, "title", ""), "status": getattr(ds, "status", ""),
            "names": names, "units": units,
            "fitted": np.array(ds["fitted"][:], dtype=float),
            "se": np.array(ds["standard_error"][:], dtype=float),
            "x": np.array(x[:], dtype=float), "x_name": getattr(x, "column", x.name),
            "measured": np.array(ds["measured"][:], dtype=float),
            "simulated": np.array(ds["simulated"][:], dtype=float),
            "measured_name": getattr(ds, "measured", "measured"),
            "measured_units": _units(ds["measured"], getattr(ds, "measured", "")),
            "x_units": getattr(x, "units", None),
            "residual_norm": float(getattr(ds, "residual_norm", np.nan)),
        }


def _units(var, name):
    """The measured output's units: the variable's attribute (files since the attribute was
    written), else what the name implies (traction_coefficient is a ratio; a force's units
    depend on the dimension, unknown here)."""
    if "units" in var.ncattrs():
        return var.units
    return "1" if name == "traction_coefficient" else None


def _axis_label(name, units):
    """'name [units]', units as the other figures write them; the name alone if unknown."""
    if units is None:
        return name
    return f"{name} [{units.replace('^2', '²')}]"


def _fmt(value, se, unit):
    unit = "" if unit in ("", "1") else " " + unit.replace("^2", "²")
    if not np.isfinite(se) or se <= 0:
        return f"{value:.6g}{unit}"
    digits = max(0, 1 - int(np.floor(np.log10(se))))
    return f"{value:.{digits}f} ± {se:.{digits}f}{unit}" if digits < 12 else f"{value:.6g}{unit}"


def plot_fit(fit, title, out, rec):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    order = np.argsort(fit["x"], kind="stable")
    x, meas, sim = fit["x"][order], fit["measured"][order], fit["simulated"][order]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    rec.line(top, 0, x, meas, "o", series="measured", quantity=fit["measured_name"], ms=4,
             mfc="none")
    label = "simulated: " + ", ".join(
        f"{n.split('.')[-1]} = {_fmt(v, s, u)}"
        for n, v, s, u in zip(fit["names"], fit["fitted"], fit["se"], fit["units"]))
    rec.line(top, 0, x, sim, "-", series=label, quantity=fit["measured_name"])
    top.set_ylabel(_axis_label(fit["measured_name"], fit.get("measured_units")))
    top.set_title(title, fontsize=9)
    top.legend(fontsize=8)
    top.grid(True, alpha=0.3)
    rec.line(bottom, 1, x, meas - sim, "o", series="measured - simulated", quantity="residual",
             ms=3)
    bottom.axhline(0.0, color="k", lw=0.8)
    bottom.set_ylabel(_axis_label("residual", fit.get("measured_units")))
    bottom.set_xlabel(_axis_label(fit["x_name"], fit.get("x_units")))
    bottom.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)
