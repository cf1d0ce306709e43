"""Figures drawn from what extract.py returns. Headless (Agg); format from the file extension."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
import numpy as np  # noqa: E402

from . import PostError, figure_format  # noqa: E402
from .extract import regime_runs  # noqa: E402

# Regimes by flag meaning: letter of the paper (E, H, S, P) and a colour-blind-safe colour
# (Okabe-Ito palette). Exterior is left unshaded in profiles.
REGIME_STYLE = {
    "exterior": ("E", "#e0e0e0"),
    "adhesion": ("H", "#56b4e9"),
    "slip": ("S", "#e69f00"),
    "plastic": ("P", "#cc79a7"),
}
UNKNOWN_STYLE = ("?", "#999999")


def save(fig, out):
    fmt = figure_format(out)
    try:
        fig.savefig(out, format=fmt, dpi=150, bbox_inches="tight")
    except OSError as e:
        raise PostError(f"{out}: cannot write: {e.strerror or e}") from None
    finally:
        plt.close(fig)


def time_axis(times):
    """(factor, unit) to show times in s, ms or us, whichever keeps the largest below 1000."""
    tmax = float(np.nanmax(np.abs(times))) if np.size(times) else 0.0
    if tmax == 0.0:
        return 1.0, "s"
    for factor, unit in ((1.0, "s"), (1e3, "ms"), (1e6, "µs")):
        if tmax * factor >= 1.0 or unit == "µs":
            return factor, unit
    return 1.0, "s"


def _regime_style(meaning):
    return REGIME_STYLE.get(meaning, UNKNOWN_STYLE)


def _regime_legend(flags, present=None, skip=("exterior",)):
    values, meanings = flags
    handles = []
    for v, m in zip(values, meanings):
        if m in skip or (present is not None and v not in present):
            continue
        letter, colour = _regime_style(m)
        handles.append(Patch(facecolor=colour, alpha=0.35 if skip else 1.0,
                             edgecolor="none", label=f"{letter}: {m}"))
    return handles


# ---- traction ------------------------------------------------------------------------------

def plot_traction(profiles, title, out):
    """One panel per record: p_x, +-g = +-mu p_n, tau_c (on the side of the net traction), with
    the regimes shaded along x (as in Figure 7 of the local-plasticity paper)."""
    n = len(profiles)
    fig, axes = plt.subplots(n, 1, figsize=(7.0, 3.2 * n + 0.6), sharex=True, squeeze=False,
                             layout="constrained")
    factor, unit = time_axis([p.time for p in profiles])
    regimes_present = set()
    for ax, p in zip(axes[:, 0], profiles):
        dx = np.diff(p.x).mean() if p.x.size > 1 else 1.0
        present = set()
        if p.regime is not None:
            values, meanings = p.regime_flags
            meaning_of = dict(zip(values, meanings))
            for i0, i1, v in regime_runs(p.regime):
                m = meaning_of.get(v)
                if m == "exterior" or v < 0:
                    continue
                present.add(v)
                ax.axvspan(p.x[i0] - dx / 2, p.x[i1 - 1] + dx / 2, color=_regime_style(m)[1],
                           alpha=0.35, lw=0)
        ax.plot(p.x, p.g, "--", color="#0072b2", lw=1.2, label=f"g = μ p_n (μ = {p.mu:g})")
        ax.plot(p.x, -p.g, "--", color="#0072b2", lw=1.2, alpha=0.6, label="−g")
        if p.tauc is not None:
            sign = -1.0 if np.nansum(p.px) < 0 else 1.0
            ax.plot(p.x, sign * p.tauc, "-.", color="#d55e00", lw=1.4,
                    label="τ_c" if sign > 0 else "−τ_c")
        ax.plot(p.x, p.px, "-", color="black", lw=1.8, label="p_x")
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.set_ylabel("traction [N/mm²]")
        ax.set_title(f"t = {p.time * factor:.4g} {unit} (record {p.index})", fontsize=10)
        ax.grid(alpha=0.25)
        regimes_present |= present
    axes[-1, 0].set_xlabel("x [mm]  (rolling: material enters at the right)")
    # One legend below the panels, so no curve is hidden behind it.
    handles, _ = axes[0, 0].get_legend_handles_labels()
    if profiles[0].regime is not None:
        handles += _regime_legend(profiles[0].regime_flags, regimes_present)
    axes[-1, 0].legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=4,
                       fontsize=8, frameon=False)
    fig.suptitle(title, fontsize=11)
    save(fig, out)


# ---- x-t maps ------------------------------------------------------------------------------

def plot_regimes(fmap, flags, title, out):
    """x-t map of the regime with categorical colours and a legend."""
    values, meanings = flags
    codes = sorted(values)
    colours = [_regime_style(dict(zip(values, meanings))[c])[1] for c in codes]
    cmap = ListedColormap(["white"] + colours)
    bounds = [-1.5] + [c - 0.5 for c in codes] + [codes[-1] + 0.5]
    norm = BoundaryNorm(bounds, cmap.N)
    factor, unit = time_axis(fmap.t_edges)
    fig, ax = plt.subplots(figsize=(7.0, 5.0), layout="constrained")
    ax.pcolormesh(fmap.x_edges, fmap.t_edges * factor, fmap.values, cmap=cmap, norm=norm,
                  shading="flat")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel(f"time [{unit}]")
    ax.legend(handles=_regime_legend(flags, skip=()), loc="upper center",
              bbox_to_anchor=(0.5, -0.12), ncol=len(codes), fontsize=9, frameon=False)
    ax.set_title(title, fontsize=11)
    save(fig, out)


def plot_plastic(ustar, tauc, title, out):
    """u* and tau_c over x and t, two pcolormesh panels with colour bars."""
    factor, unit = time_axis(ustar.t_edges)
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.6), sharey=True,
                             layout="constrained")
    for ax, fmap, cmap in ((axes[0], ustar, "viridis"), (axes[1], tauc, "magma")):
        mesh = ax.pcolormesh(fmap.x_edges, fmap.t_edges * factor, fmap.values, cmap=cmap,
                             shading="flat")
        bar = fig.colorbar(mesh, ax=ax)
        bar.set_label(f"{fmap.name} [{fmap.units}]")
        ax.set_title(fmap.long_name, fontsize=10)
        ax.set_xlabel("x [mm]")
    axes[0].set_ylabel(f"time [{unit}]")
    fig.suptitle(title, fontsize=11)
    save(fig, out)


# ---- histories -----------------------------------------------------------------------------

LEGEND_RIGHT = dict(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)


def plot_history(data, units, mu, title, out):
    """F_x/F_n, creepage, velocity, regime counts, frictional and plastic power against time."""
    t = data["time"]
    factor, unit = time_axis(t)
    t = t * factor
    style = "o-" if t.size < 2 else "-"
    fig, axes = plt.subplots(5, 1, figsize=(8.0, 10.5), sharex=True,
                             layout="constrained")
    ax = axes[0]
    ax.plot(t, data["traction_coefficient"], style, color="black", label="F_x / F_n")
    if mu is not None:
        ax.axhline(mu, ls="--", color="#0072b2", lw=1, label=f"μ = {mu:g}")
        ax.axhline(-mu, ls="--", color="#0072b2", lw=1)
        # Show 0 and the bound +-mu on the side(s) where the traction coefficient lies.
        lo = min(float(np.nanmin(data["traction_coefficient"])), 0.0)
        hi = max(float(np.nanmax(data["traction_coefficient"])), 0.0)
        hi = max(hi, mu) if hi > 0.0 or lo == 0.0 else hi
        lo = min(lo, -mu) if lo < 0.0 else lo
        ax.set_ylim(lo - 0.05 * mu, hi + 0.05 * mu)
    ax.set_ylabel("F_x / F_n [1]")
    ax.legend(**LEGEND_RIGHT)
    axes[1].plot(t, data["creepage"], style, color="#d55e00")
    axes[1].set_ylabel("creepage ξ [1]")
    axes[2].plot(t, data["velocity"], style, color="#009e73")
    axes[2].set_ylabel(f"velocity V [{units['velocity']}]")
    for name, meaning in (("n_exterior", "exterior"), ("n_adhesion", "adhesion"),
                          ("n_slip", "slip"), ("n_plastic", "plastic")):
        letter, colour = _regime_style(meaning)
        axes[3].plot(t, data[name], style, color="0.6" if meaning == "exterior" else colour,
                     label=f"{letter}: {meaning}")
    axes[3].set_ylabel("cells [1]")
    axes[3].legend(**LEGEND_RIGHT)
    axes[4].plot(t, data["frictional_power"], style, color="#e69f00", label="frictional")
    axes[4].plot(t, data["plastic_power"], style, color="#cc79a7", label="plastic")
    axes[4].set_ylabel(f"power [{units['frictional_power']}]")
    axes[4].legend(**LEGEND_RIGHT)
    axes[4].set_xlabel(f"time [{unit}]")
    for ax in axes:
        ax.grid(alpha=0.25)
    fig.suptitle(title, fontsize=11)
    fig.align_ylabels(axes)
    save(fig, out)


# ---- creep curves --------------------------------------------------------------------------

def plot_creepcurve(series, out, absolute=False, title=None):
    """Traction coefficient against creepage, one line (with markers) per series."""
    fig, ax = plt.subplots(figsize=(7.0, 4.8), layout="constrained")
    for s in series:
        x, y = (np.abs(s.creepage), np.abs(s.traction)) if absolute else (s.creepage, s.traction)
        order = np.argsort(x, kind="stable")
        ax.plot(x[order], y[order], "o-", ms=4, label=s.label)
    ax.set_xlabel("|creepage ξ| [1]" if absolute else "creepage ξ [1]")
    ax.set_ylabel("|F_x / F_n| [1]" if absolute else "traction coefficient F_x / F_n [1]")
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.axvline(0.0, color="0.5", lw=0.5)
    ax.grid(alpha=0.25)
    ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 2))
    if series:
        ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=11)
    save(fig, out)


def plot_rig(rig, title, out):
    """Twin-disc: traction coefficient per protocol step against slip (a rig's curve),
    and per revolution with the slip on a second axis."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.0, 4.4), layout="constrained")
    a1.plot(100.0 * rig.step_slip, rig.step_mu, "o-", ms=5)
    a1.set_xlabel("slip (V1 - V2)/V [%] (mean over the step's window)")
    a1.set_ylabel("traction coefficient F_x / F_n [1]")
    a1.set_title("per protocol step", fontsize=10)
    a1.grid(alpha=0.25)
    a2.plot(rig.rev_index, rig.rev_mu, "-", color="C0")
    a2.set_xlabel("revolution of disc 1")
    a2.set_ylabel("traction coefficient F_x / F_n [1]", color="C0")
    a2.grid(alpha=0.25)
    b = a2.twinx()
    b.plot(rig.rev_index, 100.0 * rig.rev_slip, "--", color="C1")
    b.set_ylabel("slip [%]", color="C1")
    a2.set_title("per revolution (mean)", fontsize=10)
    if title:
        fig.suptitle(title, fontsize=11)
    save(fig, out)
