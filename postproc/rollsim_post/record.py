"""The data behind a figure, recorded at the moment each series is drawn (`--data OUT.csv`).

Every plotting function draws through a Recorder, so the CSV holds exactly the arrays handed to
matplotlib: one row per plotted point, with the panel it is in, the series' legend label, what the
y values are (`quantity`), and, for a sweep file, the swept keys' values of the point the series
shows (one column per dotted key). Tests compare these rows with the netCDF values.

Maps of 3D fields add a column `value`: their rows are cells (x, y in mm, value the colour drawn)
or arrows (x, y of the arrow's base, value one component); figures without maps have no such
column.
"""
import csv

import numpy as np

from . import PostError


class Recorder:
    def __init__(self):
        self.rows = []    # (panel, panel_title, series, quantity, point dict, x, y, value|None)
        self.keys = []    # dotted keys of the point columns, in order of appearance

    def line(self, ax, panel, x, y, *fmt, series="", quantity="", point=None, **style):
        """ax.plot(x, y, *fmt, label=series, **style), and the points recorded."""
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        artists = ax.plot(x, y, *fmt, label=series if series else "_nolegend_", **style)
        self.add(panel, ax.get_title(), series, quantity, point, x, y)
        return artists

    def add(self, panel, title, series, quantity, point, x, y, value=None):
        """Rows x, y (and, for maps, value) as drawn; arrays of the same size."""
        point = dict(point or {})
        for k in point:
            if k not in self.keys:
                self.keys.append(k)
        x, y = np.ravel(x), np.ravel(y)
        if value is not None:
            value = np.ravel(np.asarray(value, dtype=np.float64))
        self.rows.append((panel, title, series, quantity, point, x, y, value))

    def add_map(self, panel, title, series, quantity, point, x, y, value):
        """A field drawn over the cells (x, y): the cell centres and the value shown there."""
        self.add(panel, title, series, quantity, point, x, y, value)

    def retitle(self, panel, title):
        """Panel titles are set after the lines in some figures: fix them in the rows."""
        self.rows = [(p, title if p == panel else t, s, q, pt, x, y, v)
                     for p, t, s, q, pt, x, y, v in self.rows]

    def write(self, path):
        """CSV: panel,panel_title,series,quantity,<swept keys...>,x,y[,value]; floats via repr()."""
        try:
            f = open(path, "w", newline="")
        except OSError as e:
            raise PostError(f"{path}: cannot write: {e.strerror or e}") from None
        with f:
            w = csv.writer(f, lineterminator="\n")
            maps = any(r[7] is not None for r in self.rows)
            w.writerow(["panel", "panel_title", "series", "quantity"] + self.keys + ["x", "y"] +
                       (["value"] if maps else []))
            for panel, title, series, quantity, point, x, y, value in self.rows:
                head = [panel, title, series, quantity] + [repr(float(point[k])) if k in point
                                                          else "" for k in self.keys]
                if not maps:
                    for xi, yi in zip(x.tolist(), y.tolist()):
                        w.writerow(head + [repr(xi), repr(yi)])
                    continue
                vals = value.tolist() if value is not None else [None] * x.size
                for xi, yi, vi in zip(x.tolist(), y.tolist(), vals):
                    w.writerow(head + [repr(xi), repr(yi), "" if vi is None else repr(vi)])
        return len(self.rows)
