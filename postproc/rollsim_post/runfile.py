"""Open rollsim output files and read them with clear, user-facing errors.

A *run file* (rollsim run) has the record dimension `time` and, for fields, `x`. A *sweep file*
(rollsim sweep) has one dimension per swept key; its coordinate variable is named after the dotted
key with dots replaced by underscores (plasticity.k_rel -> plasticity_k_rel) and carries the dotted
key in the attribute `key`. Both carry the global attributes of docs/file-format.md (title, case,
status, ...).
"""
import os

import netCDF4
import numpy as np

from . import PostError

# docs/case-file.md: friction.mu defaults to 0.5 when the case does not give it.
DEFAULT_MU = 0.5

# Fallback when the regime variable lacks flag_values/flag_meanings (docs/file-format.md).
DEFAULT_REGIME_FLAGS = ([0, 1, 2, 3], ["exterior", "adhesion", "slip", "plastic"])


def _is_netcdf(path):
    """True if the file starts with a netCDF classic (CDF\\x01/\\x02/\\x05) or HDF5 signature."""
    with open(path, "rb") as f:
        head = f.read(8)
    return head[:3] == b"CDF" or head == b"\x89HDF\r\n\x1a\n"


class RunFile:
    """One open rollsim netCDF file (run or sweep). Use as a context manager."""

    def __init__(self, path):
        self.path = path
        if not os.path.exists(path):
            raise PostError(f"{path}: no such file")
        if os.path.isdir(path):
            raise PostError(f"{path}: is a directory, not a netCDF file")
        try:
            netcdf = _is_netcdf(path)
        except OSError as e:
            raise PostError(f"{path}: cannot read: {e.strerror}") from None
        if not netcdf:
            raise PostError(f"{path}: not a netCDF file")
        try:
            self.ds = netCDF4.Dataset(path, "r")
        except OSError as e:
            raise PostError(f"{path}: cannot open as netCDF: {e}") from None
        self.ds.set_auto_mask(True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        if getattr(self, "ds", None) is not None and self.ds.isopen():
            self.ds.close()

    # ---- attributes -------------------------------------------------------------------------

    def attr(self, name, default=None):
        return getattr(self.ds, name) if name in self.ds.ncattrs() else default

    @property
    def title(self):
        return self.attr("title", "")

    @property
    def status(self):
        return self.attr("status", "")

    @property
    def case_text(self):
        return self.attr("case", "")

    def case(self):
        """The `case` attribute parsed into nested dicts ({} if absent)."""
        return parse_case(self.case_text)

    def mu(self):
        """Coefficient of friction friction.mu from the case text, or the v1 default 0.5."""
        value = case_value(self.case(), "friction.mu")
        if value is None:
            return DEFAULT_MU
        try:
            return float(value)
        except (TypeError, ValueError):
            raise PostError(f"{self.path}: case attribute: friction.mu is not a number: {value!r}")

    # ---- variables --------------------------------------------------------------------------

    def has(self, name):
        return name in self.ds.variables

    def variable(self, name):
        """The netCDF4 Variable `name`; PostError naming the file and variable if absent."""
        if name not in self.ds.variables:
            avail = ", ".join(sorted(self.ds.variables))
            raise PostError(f"{self.path}: no variable '{name}' (the file has: {avail})")
        return self.ds.variables[name]

    def dims(self, name):
        return tuple(self.variable(name).dimensions)

    def values(self, name):
        """All values of `name` as a float64 array (missing/fill values -> NaN).
        Integer and byte variables come back as float64 too; use raw() for the stored type."""
        data = self.variable(name)[...]
        return np.ma.filled(np.ma.asarray(data, dtype=np.float64), np.nan)

    def raw(self, name):
        """All values of `name` as stored (masked array, stored dtype)."""
        return np.ma.asarray(self.variable(name)[...])

    def units(self, name):
        var = self.variable(name)
        return getattr(var, "units", "") if "units" in var.ncattrs() else ""

    def long_name(self, name):
        var = self.variable(name)
        return getattr(var, "long_name", name) if "long_name" in var.ncattrs() else name

    # ---- run structure ----------------------------------------------------------------------

    def n_records(self):
        return len(self.ds.dimensions["time"]) if "time" in self.ds.dimensions else 0

    def require_records(self):
        """Raise if the file holds no records (e.g. a run that failed before the first output)."""
        if self.n_records() == 0:
            status = f" (status: {self.status})" if self.status else ""
            raise PostError(f"{self.path}: no records stored{status}")

    def regime_flags(self):
        """(values, meanings) of the regime flag, from the variable's CF attributes."""
        var = self.variable("regime")
        attrs = var.ncattrs()
        if "flag_values" in attrs and "flag_meanings" in attrs:
            values = [int(v) for v in np.atleast_1d(var.flag_values)]
            meanings = str(var.flag_meanings).split()
            if len(values) == len(meanings):
                return values, meanings
        return DEFAULT_REGIME_FLAGS

    def is_3d(self):
        """A 3D (elliptic contact) file: global attribute dimension = 3, or a `y` dimension,
        or the 3D-only variables Fy/py (docs/file-format.md, "Run files"). 2D files carry
        dimension = 2 or no such attribute."""
        dim = self.attr("dimension")
        if dim is not None:
            try:
                return int(np.ravel(dim)[0]) == 3
            except (TypeError, ValueError):
                pass
        return "y" in self.ds.dimensions or self.has("Fy") or self.has("py")

    def require_2d(self, command, instead):
        """PostError for a 3D file given to a 2D-only figure, saying what to use instead."""
        if self.is_3d():
            raise PostError(f"{self.path}: a 3D file (elliptic contact): {command} draws 2D "
                            f"line-contact profiles; use {instead}")

    def require_3d(self, command):
        if not self.is_3d():
            raise PostError(f"{self.path}: not a 3D file (no y dimension, Fy or "
                            f"dimension = 3 attribute): {command} needs 3D output")

    def is_sweep(self, name="traction_coefficient"):
        """A sweep file holds `name` over swept-key dimensions (anything besides time)."""
        return any(d != "time" for d in self.dims(name))

    def sweep_key(self, dim):
        """Dotted case key of a sweep dimension: the coordinate's `key` attribute, else the name."""
        if dim in self.ds.variables and "key" in self.ds.variables[dim].ncattrs():
            return str(self.ds.variables[dim].key)
        return dim

    def coordinate(self, dim):
        """Values along dimension `dim`: its coordinate variable, else the index 0..n-1."""
        var = self.ds.variables.get(dim)
        if var is not None and tuple(var.dimensions) == (dim,):
            return self.values(dim)
        return np.arange(len(self.ds.dimensions[dim]), dtype=np.float64)


def open_run(path):
    return RunFile(path)


# ---- the `case` attribute (YAML text as run) ------------------------------------------------

def parse_case(text):
    """Parse the case YAML text into nested dicts. Uses PyYAML when installed; otherwise a small
    parser for block mappings of scalars (enough for friction.mu and other plain keys)."""
    if not text:
        return {}
    try:
        import yaml
    except ImportError:
        return _parse_block_mappings(text)
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        return _parse_block_mappings(text)
    return data if isinstance(data, dict) else {}


def _parse_block_mappings(text):
    root = {}
    stack = [(-1, root)]  # (indent, mapping)
    for line in text.splitlines():
        content = line.split(" #", 1)[0].rstrip() if not line.lstrip().startswith("#") else ""
        if not content.strip() or ":" not in content:
            continue
        indent = len(content) - len(content.lstrip())
        key, _, value = content.strip().partition(":")
        while stack[-1][0] >= indent:
            stack.pop()
        parent = stack[-1][1]
        value = value.strip()
        if value == "":
            child = {}
            parent[key] = child
            stack.append((indent, child))
        else:
            parent[key] = value.strip('"').strip("'")
    return root


def case_value(case, dotted):
    """Value of a dotted key (e.g. "friction.mu") in the parsed case, or None. Numeric strings
    (PyYAML reads "-4e-4" as a string under YAML 1.1) are returned as floats."""
    node = case
    for part in dotted.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    if isinstance(node, str):
        try:
            return float(node)
        except ValueError:
            return node
    return node
