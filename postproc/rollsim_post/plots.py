"""Figures drawn from what extract.py returns. Headless (Agg); format from the file extension."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
import numpy as np  # noqa: E402

from . import PostError, figure_format  # noqa: E402
from .extract import regime_runs  # noqa: E402
from .record import Recorder  # noqa: E402

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

def plot_traction(profiles, title, out, rec=None):
    """One panel per record: p_x, +-g = +-mu p_n, tau_c (on the side of the net traction), with
    the regimes shaded along x (as in Figure 7 of the local-plasticity paper)."""
    rec = rec or Recorder()
    n = len(profiles)
    fig, axes = plt.subplots(n, 1, figsize=(7.0, 3.2 * n + 0.6), sharex=True, squeeze=False,
                             layout="constrained")
    factor, unit = time_axis([p.time for p in profiles])
    regimes_present = set()
    for k, (ax, p) in enumerate(zip(axes[:, 0], profiles)):
        ax.set_title(f"t = {p.time * factor:.4g} {unit} (record {p.index})" +
                     (f", y = {p.y:.4g} mm (row {p.row})" if p.y is not None else ""), fontsize=10)
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
        point = {"time": p.time}
        if p.y is not None:
            point["row_y"] = p.y   # (a column "y" would clash with the plotted y)
        g_label = "g = μ(|v_s|) p_n" if np.isnan(p.mu) else f"g = μ p_n (μ = {p.mu:g})"
        rec.line(ax, k, p.x, p.g, "--", color="#0072b2", lw=1.2, series=g_label,
                 quantity="g", point=point)
        rec.line(ax, k, p.x, -p.g, "--", color="#0072b2", lw=1.2, alpha=0.6, series="−g",
                 quantity="-g", point=point)
        if p.tauc is not None:
            sign = -1.0 if np.nansum(p.px) < 0 else 1.0
            rec.line(ax, k, p.x, sign * p.tauc, "-.", color="#d55e00", lw=1.4,
                     series="τ_c" if sign > 0 else "−τ_c", quantity="tau_c", point=point)
        rec.line(ax, k, p.x, p.px, "-", color="black", lw=1.8, series="p_x", quantity="px",
                 point=point)
        if p.py is not None:
            rec.line(ax, k, p.x, p.py, "-", color="#009e73", lw=1.6, series="p_y", quantity="py",
                     point=point)
            rec.line(ax, k, p.x, np.hypot(p.px, p.py), ":", color="0.35", lw=1.4, series="|p|",
                     quantity="abs_p", point=point)
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.set_ylabel("traction [N/mm²]")
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

def _record_map(rec, panel, title, fmap, factor):
    """The cells of an x-t map as drawn: x, time in the axis' unit, the colour's value."""
    X, T = np.meshgrid(fmap.x, fmap.t * factor)
    rec.add_map(panel, title, fmap.long_name, fmap.name, None, X, T, fmap.values)


def plot_regimes(fmap, flags, title, out, rec=None):
    """x-t map of the regime with categorical colours and a legend."""
    rec = rec or Recorder()
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
    _record_map(rec, 0, title, fmap, factor)
    save(fig, out)


def plot_plastic(ustar, tauc, title, out, rec=None):
    """u* and tau_c over x and t, two pcolormesh panels with colour bars."""
    rec = rec or Recorder()
    factor, unit = time_axis(ustar.t_edges)
    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.6), sharey=True,
                             layout="constrained")
    for k, (ax, fmap, cmap) in enumerate(((axes[0], ustar, "viridis"), (axes[1], tauc, "magma"))):
        mesh = ax.pcolormesh(fmap.x_edges, fmap.t_edges * factor, fmap.values, cmap=cmap,
                             shading="flat")
        bar = fig.colorbar(mesh, ax=ax)
        bar.set_label(f"{fmap.name} [{fmap.units}]")
        ax.set_title(fmap.long_name, fontsize=10)
        ax.set_xlabel("x [mm]")
        _record_map(rec, k, fmap.long_name, fmap, factor)
    axes[0].set_ylabel(f"time [{unit}]")
    fig.suptitle(title, fontsize=11)
    save(fig, out)


# ---- histories -----------------------------------------------------------------------------

LEGEND_RIGHT = dict(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)


def plot_history(data, units, mu, title, out, rec=None, extra=None, extra_units=None):
    """F_x/F_n, creepage, velocity, regime counts, frictional and plastic power against time.
    A 3D file (`extra`: Fy, Mz, Fn, lateral_creepage, spin) adds F_y/F_n beside F_x/F_n, a
    panel for the spin moment M_z, the lateral creepage beside ξ and a panel for the spin φ."""
    rec = rec or Recorder()
    extra_units = extra_units or {}
    t = data["time"]
    factor, unit = time_axis(t)
    t = t * factor
    style = "o-" if t.size < 2 else "-"
    three_d = extra is not None
    names = ["coefficients"] + (["moment"] if three_d else []) + ["creepage"] + \
        (["spin"] if three_d else []) + ["velocity", "counts", "power"]
    fig, axes = plt.subplots(len(names), 1, figsize=(8.0, 2.1 * len(names)), sharex=True,
                             layout="constrained")
    ax_of = dict(zip(names, axes))
    panel = {n: i for i, n in enumerate(names)}
    ax = ax_of["coefficients"]
    coeffs = [data["traction_coefficient"]]
    rec.line(ax, panel["coefficients"], t, data["traction_coefficient"], style, color="black",
             series="F_x / F_n", quantity="traction_coefficient")
    if three_d:
        fn = extra["Fn"]
        with np.errstate(divide="ignore", invalid="ignore"):
            fy_fn = np.where(fn != 0.0, extra["Fy"] / fn, np.nan)
        coeffs.append(fy_fn)
        rec.line(ax, panel["coefficients"], t, fy_fn, style, color="#d55e00", series="F_y / F_n",
                 quantity="Fy/Fn")
    if mu is not None:
        ax.axhline(mu, ls="--", color="#0072b2", lw=1, label=f"μ = {mu:g}")
        ax.axhline(-mu, ls="--", color="#0072b2", lw=1)
        # Show 0 and the bound +-mu on the side(s) where the coefficients lie.
        allc = np.concatenate([np.ravel(c) for c in coeffs])
        lo = min(float(np.nanmin(allc)) if np.isfinite(allc).any() else 0.0, 0.0)
        hi = max(float(np.nanmax(allc)) if np.isfinite(allc).any() else 0.0, 0.0)
        hi = max(hi, mu) if hi > 0.0 or lo == 0.0 else hi
        lo = min(lo, -mu) if lo < 0.0 else lo
        ax.set_ylim(lo - 0.05 * mu, hi + 0.05 * mu)
    ax.set_ylabel("F / F_n [1]" if three_d else "F_x / F_n [1]")
    ax.legend(**LEGEND_RIGHT)
    if three_d:
        ax = ax_of["moment"]
        rec.line(ax, panel["moment"], t, extra["Mz"], style, color="black", series="M_z",
                 quantity="Mz")
        ax.set_ylabel(f"spin moment M_z [{extra_units.get('Mz', 'N mm')}]")
    ax = ax_of["creepage"]
    rec.line(ax, panel["creepage"], t, data["creepage"], style, color="#d55e00",
             series="ξ (longitudinal)" if three_d else "", quantity="creepage")
    if three_d and "lateral_creepage" in extra:
        rec.line(ax, panel["creepage"], t, extra["lateral_creepage"], style, color="#0072b2",
                 series="η (lateral)", quantity="lateral_creepage")
        ax.legend(**LEGEND_RIGHT)
    ax.set_ylabel("creepages ξ, η [1]" if three_d else "creepage ξ [1]")
    if three_d:
        ax = ax_of["spin"]
        if "spin" in extra:
            rec.line(ax, panel["spin"], t, extra["spin"], style, color="#009e73", quantity="spin")
        ax.set_ylabel(f"spin φ [{extra_units.get('spin', '1/mm')}]")
    ax = ax_of["velocity"]
    rec.line(ax, panel["velocity"], t, data["velocity"], style, color="#009e73",
             quantity="velocity")
    ax.set_ylabel(f"velocity V [{units['velocity']}]")
    ax = ax_of["counts"]
    for name, meaning in (("n_exterior", "exterior"), ("n_adhesion", "adhesion"),
                          ("n_slip", "slip"), ("n_plastic", "plastic")):
        letter, colour = _regime_style(meaning)
        rec.line(ax, panel["counts"], t, data[name], style,
                 color="0.6" if meaning == "exterior" else colour,
                 series=f"{letter}: {meaning}", quantity=name)
    ax.set_ylabel("cells [1]")
    ax.legend(**LEGEND_RIGHT)
    ax = ax_of["power"]
    rec.line(ax, panel["power"], t, data["frictional_power"], style, color="#e69f00",
             series="frictional", quantity="frictional_power")
    rec.line(ax, panel["power"], t, data["plastic_power"], style, color="#cc79a7",
             series="plastic", quantity="plastic_power")
    ax.set_ylabel(f"power [{units['frictional_power']}]")
    ax.legend(**LEGEND_RIGHT)
    ax.set_xlabel(f"time [{unit}]")
    for ax in axes:
        ax.grid(alpha=0.25)
    fig.suptitle(title, fontsize=11)
    fig.align_ylabels(axes)
    save(fig, out)


# ---- creep curves --------------------------------------------------------------------------

# Distinct colours for series (Okabe-Ito, without yellow); "elastic" is always black, dashed.
SERIES_COLOURS = ["#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#999999",
                  "#882255", "#44aa99", "#332288"]
ELASTIC_STYLE = dict(color="black", ls="--", lw=1.6)


def _colour_map(labels):
    """A distinct colour per label, the same in every panel."""
    colours = {}
    for label in labels:
        if label not in colours:
            colours[label] = SERIES_COLOURS[len(colours) % len(SERIES_COLOURS)]
    return colours


def _grid(n, width=6.4, height=3.2, max_cols=2):
    ncols = 1 if n < 4 else max_cols
    nrows = -(-n // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows + 0.9),
                             sharex=True, sharey=True, squeeze=False)
    flat = list(axes.ravel())
    for ax in flat[n:]:
        ax.set_visible(False)
    return fig, axes, flat[:n]


def _legend_below(fig, axes, extra=(), ncol=4, title=None):
    """One legend under the panels with every labelled artist once (by label), and the title
    above them: the panels are laid out (tight_layout) in the space left between the two."""
    seen = {}
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            seen.setdefault(lab, h)
    for h in extra:
        seen.setdefault(h.get_label(), h)
    height = fig.get_figheight()
    rows = -(-len(seen) // ncol) if seen else 0
    bottom = (0.22 * rows + 0.12) / height if rows else 0.0
    top = 1.0 - (0.32 / height if title else 0.0)
    if title:
        fig.suptitle(title, fontsize=11, y=1.0 - 0.06 / height, va="top")
    fig.tight_layout(rect=(0.0, bottom, 1.0, top))
    if seen:
        fig.legend(list(seen.values()), list(seen.keys()), loc="lower center", ncol=ncol,
                   fontsize=8, frameon=False, bbox_to_anchor=(0.5, 0.0))


def plot_creepcurve(panels, out, absolute=False, title=None, percent=False, mu=None, rec=None):
    """Traction coefficient against creepage: one panel per entry of `panels` (title, series),
    one line with markers per series, a distinct colour per series label (the same in every
    panel), the elastic series black and dashed. With `percent` the creepage is in %; with
    `absolute` |xi| and |F_x/F_n| (the quadrant of the paper's Figure 9). Series with a surface
    temperature (sweep files of a case with a temperature: block) add T_max, dashed in the
    series' colour, on a second axis at the right."""
    rec = rec or Recorder()
    if panels and not isinstance(panels[0], tuple):
        panels = [("", panels)]  # a plain list of series: one panel
    every = [s for _, series in panels for s in series]
    # the elastic style marks the elastic curve among plastic ones; all elastic: colours
    plain = all(getattr(s, "elastic", False) for s in every)
    colours = _colour_map(s.label for s in every if plain or not getattr(s, "elastic", False))
    n = len(panels)
    fig, axes = plt.subplots(1, n, figsize=(6.6 if n == 1 else 4.6 * n, 4.6 + (0.6 if n > 1 else 0)),
                             sharey=True, squeeze=False, layout="constrained" if n == 1 else None)
    factor = 100.0 if percent else 1.0
    for k, (ax, (ptitle, series)) in enumerate(zip(axes[0], panels)):
        if ptitle:
            ax.set_title(ptitle, fontsize=10)
        for s in series:
            x, y = (np.abs(s.creepage), np.abs(s.traction)) if absolute else (s.creepage, s.traction)
            order = np.argsort(x, kind="stable")
            elastic = getattr(s, "elastic", False) and not plain
            style = dict(ELASTIC_STYLE) if elastic else dict(color=colours[s.label], lw=1.4)
            marker = "" if elastic or x.size > 25 else "o-"
            if marker:
                style["marker"] = "o"
            rec.line(ax, k, x[order] * factor, y[order], ms=4, series=s.label,
                     quantity="traction_coefficient", point=getattr(s, "values", None), **style)
            err = getattr(s, "error", None)
            if err is not None and np.any(np.isfinite(err)):  # the estimated error as a band
                e = np.where(np.isfinite(err), err, 0.0)[order]
                ax.fill_between(x[order] * factor, y[order] - e, y[order] + e,
                                color=style.get("color", "k"), alpha=0.2, lw=0)
        hot = [s for s in series if getattr(s, "t_max", None) is not None]
        if hot:
            tax = ax.twinx()
            for s in hot:
                x = np.abs(s.creepage) if absolute else s.creepage
                order = np.argsort(x, kind="stable")
                colour = ELASTIC_STYLE.get("color", "k") if getattr(s, "elastic", False) \
                    and not plain else colours[s.label]
                rec.line(tax, k, x[order] * factor, s.t_max[order], color=colour, lw=1.0, ls="--",
                         series=s.label, quantity="T_max", point=getattr(s, "values", None))
            tax.set_ylabel("T_max [degC] (dashed)")
        if mu is not None:
            ax.axhline(mu if absolute else mu, color="0.4", lw=0.8, ls=":", label=f"μ = {mu:g}")
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.axvline(0.0, color="0.5", lw=0.5)
        ax.grid(alpha=0.25)
        unit = "%" if percent else "1"
        ax.set_xlabel(f"|creepage ξ| [{unit}]" if absolute else f"creepage ξ [{unit}]")
        if not percent:
            ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 2))
    axes[0, 0].set_ylabel("|F_x / F_n| [1]" if absolute else "traction coefficient F_x / F_n [1]")
    if n == 1:
        if any(series for _, series in panels):
            axes[0, 0].legend(fontsize=8)
        if title:
            axes[0, 0].set_title(title, fontsize=11)
    else:
        _legend_below(fig, axes[0], ncol=min(7, len(colours) + 2), title=title)
    save(fig, out)


# ---- sweep files: profiles per point ------------------------------------------------------

def _shade_regimes(ax, prof, present):
    if prof.regime is None:
        return
    values, meanings = prof.regime_flags
    meaning_of = dict(zip(values, meanings))
    dx = np.diff(prof.x).mean() if prof.x.size > 1 else 1.0
    for i0, i1, v in regime_runs(prof.regime):
        m = meaning_of.get(v)
        if m == "exterior" or v < 0:
            continue
        present.add(v)
        ax.axvspan(prof.x[i0] - dx / 2, prof.x[i1 - 1] + dx / 2, color=_regime_style(m)[1],
                   alpha=0.35, lw=0)


def plot_sweep_traction(panels, title, out, rec=None):
    """Profiles of sweep points. `panels`: list of (panel title, [(series label, SweepProfile)]).
    One profile in a panel: p_x (black), g = mu p_n (blue, dashed), tau_c (orange, dash-dot;
    not for an elastic point) and the regimes shaded. Several (--overlay): p_x and tau_c of each
    in its own colour (elastic: black), g once when the points share it. g and tau_c are drawn
    on the side of the net traction."""
    rec = rec or Recorder()
    fig, axes, used = _grid(len(panels))
    present = set()
    flags = None
    labels = [lab for _, profs in panels for lab, p in profs if not p.elastic]
    colours = _colour_map(labels)
    for k, (ax, (ptitle, profs)) in enumerate(zip(used, panels)):
        ax.set_title(ptitle, fontsize=10)
        single = len(profs) == 1
        sign = -1.0 if np.nansum(profs[0][1].px) < 0 else 1.0
        same_g = all(np.array_equal(p.g, profs[0][1].g, equal_nan=True) for _, p in profs)
        for j, (label, p) in enumerate(profs):
            pt = p.point.values
            if single:
                _shade_regimes(ax, p, present)
                flags = flags or p.regime_flags
            if j == 0 or not same_g:
                g_colour = "#0072b2" if single else "0.45" if same_g else colours.get(label, "black")
                rec.line(ax, k, p.x, sign * p.g, ls="--" if same_g else ":", color=g_colour,
                         lw=1.2, series="g = μ p_n" if same_g else f"g, {label}", quantity="g",
                         point=pt)
            colour = "black" if single or p.elastic else colours[label]
            if p.tauc is not None:
                rec.line(ax, k, p.x, sign * p.tauc, "-.", lw=1.4,
                         color="#d55e00" if single else colour,
                         series="τ_c" if single else f"τ_c, {label}", quantity="tau_c", point=pt)
            rec.line(ax, k, p.x, p.px, "-", lw=1.8, color=colour,
                     series="p_x" if single else f"p_x, {label}", quantity="px", point=pt)
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.grid(alpha=0.25)
    for ax in used:
        if ax.get_subplotspec().is_first_col():
            ax.set_ylabel("traction [N/mm²]")
        if ax.get_subplotspec().is_last_row() or ax is used[-1]:
            ax.set_xlabel("x [mm]  (material enters at the right)")
            ax.xaxis.set_tick_params(labelbottom=True)
    extra = _regime_legend(flags, present) if flags else []
    _legend_below(fig, used, extra, title=title)
    save(fig, out)


def plot_sweep_regimes(panels, flags, row_name, title, out, rec=None):
    """Regime maps of sweep points: `panels` is a list of (panel title, rows) with rows a list of
    (row label, SweepProfile); one row per point along the swept key `row_name`."""
    rec = rec or Recorder()
    values, meanings = flags
    codes = sorted(values)
    colours = [_regime_style(dict(zip(values, meanings))[c])[1] for c in codes]
    cmap = ListedColormap(["white"] + colours)
    norm = BoundaryNorm([-1.5] + [c - 0.5 for c in codes] + [codes[-1] + 0.5], cmap.N)
    n = len(panels)
    nrows_max = max(len(rows) for _, rows in panels)
    fig, axes = plt.subplots(n, 1, figsize=(7.0, min(1.2 + 0.3 * nrows_max, 6.0) * n + 1.0),
                             squeeze=False, sharex=True)
    for k, (ax, (ptitle, rows)) in enumerate(zip(axes[:, 0], panels)):
        x = rows[0][1].x
        grid = np.array([r.regime for _, r in rows])
        from .extract import cell_edges
        ax.pcolormesh(cell_edges(x), np.arange(len(rows) + 1) - 0.5, grid, cmap=cmap, norm=norm,
                      shading="flat")
        ax.set_yticks(range(len(rows)), [lab for lab, _ in rows], fontsize=8)
        ax.set_ylabel(row_name)
        ax.set_title(ptitle, fontsize=10)
        for lab, r in rows:
            rec.add(k, ptitle, lab, "regime", r.point.values, x, r.regime)
    axes[-1, 0].set_xlabel("x [mm]  (material enters at the right)")
    _legend_below(fig, [], _regime_legend(flags, skip=()), ncol=len(codes), title=title)
    save(fig, out)


def plot_sweep_plastic(panels, title, out, rec=None):
    """u* and tau_c along x for sweep points: one row of two panels per entry of `panels`
    (title, [(label, x, ustar, tauc or None, point)]), one line per point."""
    rec = rec or Recorder()
    n = len(panels)
    fig, axes = plt.subplots(n, 2, figsize=(11.0, 2.8 * n + 1.0), squeeze=False, sharex=True)
    labels = [lab for _, lines in panels for lab, *_ in lines]
    colours = _colour_map(labels)
    for k, (row, (ptitle, lines)) in enumerate(zip(axes, panels)):
        row[0].set_title(f"{ptitle}: accumulated plastic deformation" if ptitle else
                         "accumulated plastic deformation", fontsize=10)
        row[1].set_title(f"{ptitle}: yield limit" if ptitle else "yield limit", fontsize=10)
        for lab, x, ustar, tauc, point in lines:
            c = colours[lab] if len(lines) > 1 else "black"
            rec.line(row[0], 2 * k, x, ustar, "-", color=c, lw=1.5, series=lab, quantity="ustar",
                     point=point)
            if tauc is not None:
                rec.line(row[1], 2 * k + 1, x, tauc, "-", color=c, lw=1.5, series=lab,
                         quantity="tau_c", point=point)
        row[0].set_ylabel("u* [mm]")
        row[1].set_ylabel("τ_c [N/mm²]")
        for ax in row:
            ax.grid(alpha=0.25)
    for ax in axes[-1]:
        ax.set_xlabel("x [mm]  (material enters at the right)")
    _legend_below(fig, axes[:, 0], ncol=4, title=title)
    save(fig, out)


def plot_rig(rig, title, out, rec=None):
    """Twin-disc: traction coefficient per protocol step against slip (a rig's curve),
    and per revolution with the slip on a second axis; with a temperature: block a third
    panel, the surface temperatures per revolution."""
    rec = rec or Recorder()
    temps = rig.rev_temperature
    if temps:
        fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(15.5, 4.4), layout="constrained")
    else:
        fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.0, 4.4), layout="constrained")
    a1.set_title("per protocol step", fontsize=10)
    a2.set_title("per revolution (mean)", fontsize=10)
    rec.line(a1, 0, 100.0 * rig.step_slip, rig.step_mu, "o-", ms=5, series="step",
             quantity="traction_coefficient")
    a1.set_xlabel("slip (V1 - V2)/V [%] (mean over the step's window)")
    a1.set_ylabel("traction coefficient F_x / F_n [1]")
    a1.grid(alpha=0.25)
    rec.line(a2, 1, rig.rev_index, rig.rev_mu, "-", color="C0", series="revolution",
             quantity="traction_coefficient")
    a2.set_xlabel("revolution of disc 1")
    a2.set_ylabel("traction coefficient F_x / F_n [1]", color="C0")
    a2.grid(alpha=0.25)
    b = a2.twinx()
    rec.add(1, a2.get_title(), "revolution", "slip_percent", None, rig.rev_index,
            100.0 * rig.rev_slip)
    b.plot(rig.rev_index, 100.0 * rig.rev_slip, "--", color="C1")
    b.set_ylabel("slip [%]", color="C1")
    if temps:
        a3.set_title("surface temperature per revolution", fontsize=10)
        labels = {"revolution_T_max": ("largest in the contact", "-", "C3"),
                  "revolution_inlet_temperature_1": ("entering the contact: disc 1", "-", "C0"),
                  "revolution_inlet_temperature_2": ("entering the contact: disc 2", ":", "C2"),
                  "revolution_bulk_temperature_1": ("bulk: disc 1", "--", "C0"),
                  "revolution_bulk_temperature_2": ("bulk: disc 2", "-.", "C2")}
        for name, (label, style, colour) in labels.items():
            if name in temps:
                rec.line(a3, 2, rig.rev_index, temps[name], style, color=colour, series=label,
                         quantity="temperature_degC")
        a3.set_xlabel("revolution of disc 1")
        a3.set_ylabel("temperature [°C]")
        a3.grid(alpha=0.25)
        a3.legend(fontsize=8)
    if title:
        fig.suptitle(title, fontsize=11)
    save(fig, out)


def plot_friction(prof, title, out, rec=None):
    """Velocity-dependent friction at one record: mu along x (left) and mu against the slip
    speed |v_s| of every contact cell over the law's curve (right)."""
    rec = rec or Recorder()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10.0, 3.8), layout="constrained")
    inside = np.isfinite(prof.mu)
    point = {"time": prof.time}
    if prof.y is None:
        rec.line(a1, 0, prof.x[inside], prof.mu[inside], "-", color="black", lw=1.6,
                 series="mu", quantity="mu", point=point)
        a1.set_ylabel("μ")
        a1.set_title(f"μ along the contact (record {prof.index})", fontsize=10)
        a1.grid(alpha=0.25)
    else:  # 3D: mu over the patch (cells outside the contact blank)
        from .extract import cell_edges
        mesh = a1.pcolormesh(cell_edges(prof.x), cell_edges(prof.y),
                             np.ma.masked_invalid(prof.mu), cmap="viridis", shading="flat")
        fig.colorbar(mesh, ax=a1).set_label("μ")
        a1.set_aspect("equal")
        a1.set_ylabel("y [mm]")
        a1.set_title(f"μ over the contact (record {prof.index})", fontsize=10)
        X, Y = np.meshgrid(prof.x, prof.y)
        rec.add_map(0, a1.get_title(), "mu", "mu", point, X[inside], Y[inside], prof.mu[inside])
    a1.set_xlabel("x [mm]  (rolling: material enters at the right)")
    s = prof.slip_speed[inside]
    if prof.law is not None and s.size:
        curve = np.linspace(0.0, max(float(np.nanmax(s)) * 1.1, 1e-9), 200)
        rec.line(a2, 1, curve, prof.law(curve), "-", color="#0072b2", lw=1.2,
                 series=f"law ({prof.law_name})", quantity="mu_law", point=point)
    rec.line(a2, 1, s, prof.mu[inside], "o", color="black", ms=3, series="cells",
             quantity="mu", point=point)
    a2.set_xlabel("slip speed |v_s| [mm/s]")
    a2.set_ylabel("μ")
    a2.set_title("μ against slip speed, every contact cell", fontsize=10)
    a2.grid(alpha=0.25)
    a2.legend(fontsize=8)
    fig.suptitle(title, fontsize=11)
    fig.savefig(out)
    plt.close(fig)


def plot_profiles(prof, title, out, rec=None):
    """Rail and wheel profiles (a case's profiles: block, rollsim_post.profiles): the rail
    inclined by rail_inclination, the wheel lowered onto it where both are functions of y,
    the point where they touch marked; y toward the track centre, z downward (drawn
    downward)."""
    from .profiles import place_rail, wheel_drop
    rec = rec or Recorder()
    fig, ax = plt.subplots(figsize=(8.0, 5.0), layout="constrained")
    ax.set_title(title, fontsize=10)
    rail = None
    if prof["rail"] is not None:
        rail = place_rail(*prof["rail"], prof["rail_inclination"])
        theta = prof["rail_inclination"]
        label = "rail" + (f" (inclined {theta:.4g} rad, 1:{1.0 / math.tan(abs(theta)):.4g})"
                          if theta else "")
        rec.line(ax, 0, rail[0], rail[1], "-", color="C0", series=label, quantity="z_mm")
        top = float(np.min(rail[1]))
        ax.axhline(top + prof["gauge_height"], color="C0", ls=":", lw=0.8,
                   label=f"gauge height, {prof['gauge_height']:g} mm below the rail's top")
    contact = prof.get("contact")
    if prof["wheel"] is not None:
        wy, wz = prof["wheel"]
        shift = contact["wheel_shift"] if contact else 0.0
        wy = wy + shift
        drop, at = wheel_drop(rail, (wy, wz)) if rail is not None else (0.0, None)
        moved = f" (moved {shift:+.3f} mm in y, {drop:+.3f} mm in z to touch the rail)" if contact \
            else f" (moved {drop:+.3f} mm in z to touch the rail)"
        label = "wheel" + (moved if at is not None else "")
        rec.line(ax, 0, wy, wz + drop, "-", color="C3", series=label, quantity="z_mm")
        if at is not None and not contact:
            zc = float(np.interp(at, rail[0], rail[1]))
            rec.line(ax, 0, [at], [zc], "o", color="k", ms=5,
                     series="first point of contact (rigid)", quantity="z_mm")
    for k, p in enumerate(contact["patches"] if contact else []):
        # the normal into the wheel: the rail's tangent (cos, sin) turned up (z downward)
        d = math.radians(p["angle"])
        ny, nz = math.sin(d), -math.cos(d)
        label = (f"patch {k + 1}: {p['angle']:.2f} deg, F_n {p['fn'] / 1000.0:.3g} kN, "
                 f"p_max {p['p_max']:.0f} N/mm^2")
        rec.line(ax, 0, [p["y"]], [p["z"]], "o", color=f"C{2 + k}", ms=6, series=label,
                 quantity="z_mm")
        ax.annotate("", xy=(p["y"] + 6.0 * ny, p["z"] + 6.0 * nz), xytext=(p["y"], p["z"]),
                    arrowprops={"arrowstyle": "->", "color": f"C{2 + k}", "lw": 1.2})
    ax.set_xlabel("y [mm], toward the track centre")
    ax.set_ylabel("z [mm], downward")
    ax.invert_yaxis()
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.25)
    ax.legend(fontsize=8, loc="best")
    save(fig, out)


def plot_wheelrail(d, title, out, rec=None):
    """A sweep on profiles against the lateral displacement (a moving wheelset's run file against
    time): each patch's contact point on the rail and contact angle, its normal and tangential
    forces, and the lateral force on the wheel in track coordinates (docs/file-format.md
    "Wheel-rail sweep files")."""
    rec = rec or Recorder()
    # a moving wheelset's file (rollsim run) is drawn against time, the displacement in panel 1
    over_time = "time" in d and isinstance(d["time"], np.ndarray)
    y = d["time"] if over_time else d["lateral_displacement"]
    npatch = d["Fn"].shape[1]
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 7.0), layout="constrained", sharex=True)
    fig.suptitle(title, fontsize=10)
    panels = [
        (axes[0, 0], "contact point on the rail", "y on the rail [mm], toward the track centre",
         [("rail_y", 1.0, "y_mm")]),
        (axes[0, 1], "contact angle", "contact angle [deg]",
         [("contact_angle", 180.0 / math.pi, "angle_deg")]),
        (axes[1, 0], "forces on the wheel per patch", "force [kN]",
         [("Fn", 1e-3, "Fn_kN"), ("Fx", 1e-3, "Fx_kN"), ("Fs", 1e-3, "Fs_kN")]),
    ]
    styles = {"Fn": "-", "Fx": "--", "Fs": ":"}
    for panel, (ax, name, ylabel, series) in enumerate(panels):
        ax.set_title(name, fontsize=9)
        for j, (var, scale, quantity) in enumerate(series):
            for k in range(npatch):
                v = d[var][:, k] * scale
                if not np.any(np.isfinite(v)):
                    continue
                label = f"patch {k + 1}" if len(series) == 1 else f"{var}, patch {k + 1}"
                rec.line(ax, panel, y, v, styles.get(var, "-"), marker="o", ms=3,
                         color=f"C{(k * len(series) + j) % 10}", series=label, quantity=quantity)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.25)
        ax.legend(fontsize=7, loc="best")
    ax = axes[1, 1]
    ax.set_title("lateral and vertical force on the wheel (track coordinates)", fontsize=9)
    rec.line(ax, 3, y, d["Fy_track"] * 1e-3, "-", marker="o", ms=3, color="C0",
             series="F_y toward the track centre", quantity="Fy_kN")
    rec.line(ax, 3, y, d["Fz_track"] * 1e-3, "--", marker="o", ms=3, color="C1",
             series="F_z up", quantity="Fz_kN")
    ax.set_ylabel("force [kN]")
    ax.grid(alpha=0.25)
    ax.legend(fontsize=7, loc="best")
    if over_time:
        rec.line(axes[0, 0], 0, y, d["lateral_displacement"], "--", color="k",
                 series="lateral displacement of the wheelset", quantity="y_mm")
        axes[0, 0].set_ylabel("mm: y on the rail, lateral displacement")
        axes[0, 0].legend(fontsize=7, loc="best")
    for ax in axes[1]:
        ax.set_xlabel("time [s]" if over_time else
                      "lateral displacement of the wheelset toward the rail [mm]")
    save(fig, out)
