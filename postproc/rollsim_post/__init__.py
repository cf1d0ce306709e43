"""Post-processing of rollsim netCDF output (docs/file-format.md).

Modules, one concept each:
  runfile   open a run or sweep file, read variables, parse the `case` attribute
            (errors -> PostError)
  extract   numbers for every figure and the CSV export: nearest record, traction profiles, regime
            maps, histories, creep-curve series (single-run files and sweep files), export tables
  plots     matplotlib figures (Agg) drawn from what `extract` returns; no file reading
  cli       the command line: argument parsing and dispatch
"""


class PostError(Exception):
    """A user-facing error: the message names the file and/or variable. The CLI prints it on stderr
    and exits with status 2."""


FIGURE_FORMATS = {".png": "png", ".svg": "svg", ".pdf": "pdf"}


def figure_format(out):
    """The figure format for an output path, from its extension (PostError if unsupported).
    Kept here, not in plots.py, so a bad -o is reported before matplotlib is imported."""
    import os
    ext = os.path.splitext(out)[1].lower()
    if ext not in FIGURE_FORMATS:
        raise PostError(f"{out}: unsupported figure format '{ext or '(none)'}': "
                        "use .png, .svg or .pdf")
    return FIGURE_FORMATS[ext]
