"""Figures of 3D (elliptic contact) files: field maps over the patch and creep curves in F_x, F_y,
M_z. Drawn from what field3d.py returns; every drawn number goes through the Recorder."""
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import BoundaryNorm, ListedColormap

from .extract import cell_edges
from .field3d import CREEP_SYMBOLS, FORCE_SYMBOLS, arrow_cells, contact_edges
from .plots import (ELASTIC_STYLE, SERIES_COLOURS, _regime_legend, _regime_style, plt, save,
                    time_axis)
from .record import Recorder
from .sweep import describe

SEQUENTIAL = {"traction": "viridis", "slip": "cividis", "pressure": "Greys", "ustar": "viridis",
              "tauc": "magma", "upl": "viridis"}


NON_NEGATIVE = ("traction", "slip", "pressure", "ustar", "upl")


def pretty_units(u):
    """N/mm2 -> N/mm², as the 2D figures write units."""
    return (u or "").replace("mm2", "mm²").replace("mm3", "mm³")


def _map_grid(n):
    ncols = min(n, 2)
    nrows = -(-n // ncols)
    return ncols, nrows


def plot_map(maps, title, out, rec=None, max_arrows=25):
    """One panel per record: the field's colour over the cells (equal aspect, colour bar), the
    discrete contact edge (cell sides between contact and exterior, black) and the ellipse
    (Hertz from the file's attributes, else fitted to the contact cells; dashed); vector fields
    (traction, slip, upl) with arrows on the cells in contact (every k-th cell)."""
    rec = rec or Recorder()
    m0 = maps[0]
    ex, ey = cell_edges(m0.x), cell_edges(m0.y)
    aspect = (ey[-1] - ey[0]) / max(ex[-1] - ex[0], 1e-300)
    ncols, nrows = _map_grid(len(maps))
    w = 5.6
    fig, axes = plt.subplots(nrows, ncols,
                             figsize=(w * ncols, ((w - 1.2) * aspect + 1.0) * nrows + 0.8),
                             squeeze=False, layout="constrained")
    flat = list(axes.ravel())
    for ax in flat[len(maps):]:
        ax.set_visible(False)
    factor, unit = time_axis([m.time for m in maps if m.time is not None])
    for k, (ax, m) in enumerate(zip(flat, maps)):
        if m.time is None:   # a sweep point
            ptitle, point = m.label, dict(m.index.values)
        else:
            ptitle = m.label or f"t = {m.time * factor:.4g} {unit} (record {m.index})"
            point = {"time": m.time}
        ax.set_title(ptitle, fontsize=10)
        X, Y = np.meshgrid(m.x, m.y)
        if m.field == "regime":
            values, meanings = m.regime_flags
            codes = sorted(values)
            colours = [_regime_style(dict(zip(values, meanings))[c])[1] for c in codes]
            cmap = ListedColormap(["white"] + colours)
            norm = BoundaryNorm([-1.5] + [c - 0.5 for c in codes] + [codes[-1] + 0.5], cmap.N)
            ax.pcolormesh(ex, ey, m.values, cmap=cmap, norm=norm, shading="flat")
            present = set(np.unique(m.values).tolist())
            regime_handles = _regime_legend(m.regime_flags, present, skip=())
        else:
            limits = {}
            if m.field in NON_NEGATIVE:   # magnitudes: the colour scale starts at 0
                top = float(np.nanmax(m.values)) if np.isfinite(m.values).any() else 0.0
                limits = dict(vmin=0.0, vmax=top if top > 0.0 else 1.0)
            mesh = ax.pcolormesh(ex, ey, m.values, cmap=SEQUENTIAL.get(m.field, "viridis"),
                                 shading="flat", **limits)
            bar = fig.colorbar(mesh, ax=ax, shrink=0.9)
            bar.set_label(f"{m.symbol} [{pretty_units(m.units)}]" if m.units else m.symbol)
        rec.add_map(k, ptitle, m.long_name, m.field, point, X, Y, m.values)
        # Arrows of the vector field on the cells in contact.
        if m.vx is not None:
            cells, step = arrow_cells(m, max_arrows)
            u, v = m.vx[cells], m.vy[cells]
            mag = float(np.nanmax(np.hypot(u, v))) if u.size else 0.0
            if mag > 0.0:
                spacing = step * min(abs(np.diff(ex).mean()), abs(np.diff(ey).mean()))
                ax.quiver(X[cells], Y[cells], u, v, angles="xy", scale_units="xy",
                          scale=mag / (0.9 * spacing), width=0.004, color="white",
                          edgecolor="black", linewidth=0.4, pivot="middle", minlength=0.0)
                ax.text(0.01, 0.01, f"longest arrow: {mag:.3g} {pretty_units(m.units)}", fontsize=8,
                        transform=ax.transAxes, va="bottom", ha="left",
                        bbox=dict(fc="white", ec="none", alpha=0.8))
            rec.add_map(k, ptitle, "arrows", "arrow_x", point, X[cells], Y[cells], u)
            rec.add_map(k, ptitle, "arrows", "arrow_y", point, X[cells], Y[cells], v)
        # The contact edge and the ellipse.
        segs = contact_edges(m.x, m.y, m.contact)
        # black on a white halo: visible on dark and light colours alike
        ax.add_collection(LineCollection(segs, colors="white", linewidths=2.4))
        ax.add_collection(LineCollection(segs, colors="black", linewidths=1.0,
                                         label="contact edge (p_n > 0)"))
        if segs:
            xy = np.asarray(segs, dtype=np.float64).reshape(-1, 2)
            rec.add_map(k, ptitle, "contact edge (p_n > 0)", "contact_edge", point,
                        xy[:, 0], xy[:, 1], np.full(len(xy), np.nan))
        if m.ellipse is not None:
            e = m.ellipse
            label = (f"Hertz ellipse a = {e.a:.3g}, b = {e.b:.3g} mm" if e.source == "Hertz" else
                     f"fitted ellipse a = {e.a:.3g}, b = {e.b:.3g} mm")
            px, py = e.polygon()
            ax.plot(px, py, "--", color="#d55e00", lw=1.3, label=label)
            rec.add_map(k, ptitle, label, "ellipse", point, px, py, np.full(px.size, np.nan))
            rec.add_map(k, ptitle, label, "ellipse_semi_axes", point, [e.a], [e.b], [np.nan])
            rec.add_map(k, ptitle, label, "ellipse_centre", point, [e.xc], [e.yc], [np.nan])
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]  (rolling; material enters at the right)")
        ax.set_ylabel("y [mm]")
        handles, _ = ax.get_legend_handles_labels()
        if m.field == "regime":
            handles += regime_handles
        ax.legend(handles=handles, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16),
                  ncol=2 if m.field != "regime" else 3, frameon=False)
    fig.suptitle(f"{title}\n{m0.long_name}" if title else m0.long_name, fontsize=11)
    save(fig, out)


def _value_label(key, value, units):
    """'η = 0.001', 'φ = 0.0002 1/mm': a swept key's value with its units (from the file)."""
    if key not in CREEP_SYMBOLS:
        return describe(key, value, units)
    unit = "" if units in ("", "1", None) else " " + pretty_units(units)
    return f"{CREEP_SYMBOLS[key]} = {value:.6g}{unit}"


def _key_label(key, units):
    sym = CREEP_SYMBOLS.get(key, key)
    unit = units if units and units != "1" else "1"
    return f"{sym} [{unit}]"


def plot_creep3d(panels, title, out, rec=None):
    """A grid of panels: one row per quantity (F_x, F_y, M_z), one column per swept creepage
    key; in each, one line per combination of the other swept keys (a colour per label)."""
    rec = rec or Recorder()
    keys = list(dict.fromkeys(p.key for p in panels))
    names = list(dict.fromkeys(p.var for p in panels))
    width = 6.4 if len(keys) == 1 else 4.8 * len(keys)
    fig, axes = plt.subplots(len(names), len(keys), figsize=(width, 2.9 * len(names) + 0.8),
                             squeeze=False, sharex="col", layout="constrained")
    for k, p in enumerate(panels):
        col, row = keys.index(p.key), names.index(p.var)
        ax = axes[row, col]
        colours = {}
        for s in p.series:
            if s.values:
                s.label = ", ".join(_value_label(k, v, p.series_units.get(k, ""))
                                    for k, v in s.values.items())
            c = colours.setdefault(s.label, SERIES_COLOURS[len(colours) % len(SERIES_COLOURS)])
            style = dict(ELASTIC_STYLE) if len(p.series) == 1 else dict(color=c, lw=1.4)
            style["color"] = "black" if len(p.series) == 1 else c
            style["ls"] = "-"
            rec.line(ax, k, s.creepage, s.traction, marker="o" if s.creepage.size <= 25 else "",
                     ms=3.5, series=s.label if len(p.series) > 1 else "", quantity=p.var,
                     point=s.values, **style)
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.axvline(0.0, color="0.5", lw=0.5)
        ax.grid(alpha=0.25)
        sym = FORCE_SYMBOLS.get(p.var, p.var)
        ax.set_ylabel(f"{sym} [{pretty_units(p.units)}]" if p.units else sym)
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 2))
        if row == len(names) - 1:
            ax.set_xlabel(_key_label(p.key, p.key_units))
        if row == len(names) - 1 and len(p.series) > 1:
            # one legend per column, under it: no curve hidden
            ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.22),
                      ncol=min(3, len(p.series)), frameon=False)
        rec.retitle(k, ax.get_title())
    if title:
        fig.suptitle(title, fontsize=11)
    save(fig, out)

