"""rollsim in Python: run, sweep and check cases in-process through librollsim.

    import rollsim
    ds = rollsim.run("cases/carter2d.yaml", set={"rolling.creepage": -3e-4})  # xarray.Dataset
    sw = rollsim.sweep("cases/creep_curves.yaml")
    info = rollsim.check({"contact": {"normal_load": 178.9, ...}, ...})        # dict

A case is a path to a YAML file, YAML text, or a dict (written as YAML; relative paths inside a
text or dict case, e.g. history tables, are relative to the current directory). `set` maps dotted
keys to values, as `--set KEY=VALUE` on the command line, or is a list of "KEY=VALUE" strings
(set=["rolling.creepage=-3e-4", "grid.cells=200"], values read as YAML there too). Each call
writes the command line's netCDF file to a temporary path and loads it with xarray (the data are read into memory and the
file removed), so results are those of `rollsim run/sweep -o FILE`. Errors raise CaseError with
the command line's message (file:line: key ...); `CaseError.status` is the exit status class
(2 invalid input, 3 solver failure, ...).

The library: $ROLLSIM_LIB if set, else the librollsim.so installed with this package
(`cmake --install`, which writes its place into rollsim/_installed.py), else build/librollsim.so
of the repository this package sits in (after the README's build), else librollsim.so on the
loader's path.
"""
import ctypes
import json
import os
import shutil
import tempfile
from collections.abc import Mapping

__all__ = ["run", "sweep", "check", "CaseError", "library_path", "version"]

_STATUS = {1: "internal error", 2: "invalid input", 3: "solver failure", 4: "interrupted",
           5: "output error"}


class CaseError(Exception):
    """An error of rollsim: the message is the command line's (file:line: key: what)."""

    def __init__(self, message, status):
        super().__init__(message)
        self.status = status


def library_path():
    """The librollsim.so this package loads."""
    env = os.environ.get("ROLLSIM_LIB")
    if env:
        return env
    here = os.path.dirname(os.path.abspath(__file__))
    cands = [os.path.join(here, "..", "..", "build", "librollsim.so"),
             os.path.join(here, "librollsim.so")]
    try:  # written by cmake --install: the library relative to this directory
        from ._installed import LIBRARY
        cands.insert(0, os.path.join(here, LIBRARY))
    except ImportError:
        pass
    for cand in cands:
        if os.path.exists(cand):
            return os.path.normpath(cand)
    return "librollsim.so"


_lib = None
_PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t)


def _load():
    global _lib
    if _lib is None:
        path = library_path()
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            raise ImportError(f"rollsim: cannot load {path} ({e}): build it (README) or set "
                              "ROLLSIM_LIB") from None
        sets = ctypes.POINTER(ctypes.c_char_p)
        for name in ("rs_api_run", "rs_api_sweep"):
            f = getattr(lib, name)
            f.argtypes = [ctypes.c_char_p, sets, ctypes.c_int, ctypes.c_char_p, ctypes.c_char_p,
                          ctypes.c_size_t]
            f.restype = ctypes.c_int
        lib.rs_api_sweep_progress.argtypes = [ctypes.c_char_p, sets, ctypes.c_int,
                                              ctypes.c_char_p, _PROGRESS, ctypes.c_void_p,
                                              ctypes.c_char_p, ctypes.c_size_t]
        lib.rs_api_sweep_progress.restype = ctypes.c_int
        lib.rs_api_check.argtypes = [ctypes.c_char_p, sets, ctypes.c_int,
                                     ctypes.POINTER(ctypes.c_void_p), ctypes.c_char_p,
                                     ctypes.c_size_t]
        lib.rs_api_check.restype = ctypes.c_int
        lib.rs_api_status.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p),
                                      ctypes.c_char_p, ctypes.c_size_t]
        lib.rs_api_status.restype = ctypes.c_int
        lib.rs_api_free.argtypes = [ctypes.c_void_p]
        lib.rs_api_version.restype = ctypes.c_char_p
        _lib = lib
    return _lib


def version():
    return _load().rs_api_version().decode()


def _yaml_value(v):
    """A Python value as YAML flow text for --set (JSON is YAML)."""
    if isinstance(v, str):
        return v
    return json.dumps(v)


def _sets(set):
    """The --set arguments of `set`: a mapping {dotted key: value}, or a list (tuple) of
    "KEY=VALUE" strings (a single string is one of them)."""
    if set is None:
        items = []
    elif isinstance(set, Mapping):
        items = [f"{k}={_yaml_value(v)}" for k, v in set.items()]
    elif isinstance(set, (str, list, tuple)):
        items = [set] if isinstance(set, str) else list(set)
        for s in items:
            if not isinstance(s, str) or "=" not in s or s.startswith("="):
                raise TypeError(f"set=: a list item must be a 'KEY=VALUE' string (as --set "
                                f"KEY=VALUE), got {s!r}")
    else:
        raise TypeError("set= takes a dict {dotted key: value} or a list of 'KEY=VALUE' "
                        f"strings, got {type(set).__name__}")
    arr = (ctypes.c_char_p * max(1, len(items)))(*[s.encode() for s in items])
    return arr, len(items)


class _Case:
    """The case as a file path: the given path, or a temporary file for text and dicts."""

    def __init__(self, case):
        self.tmp = None
        if isinstance(case, dict):
            import yaml
            case = yaml.safe_dump(case, sort_keys=False)
        if isinstance(case, os.PathLike) or (isinstance(case, str) and "\n" not in case
                                             and case.strip().endswith((".yaml", ".yml"))):
            self.path = os.fspath(case)
            self.label = None
        elif isinstance(case, str):
            self.tmp = tempfile.mkdtemp(prefix="rollsim_")
            self.path = os.path.join(self.tmp, "case.yaml")
            with open(self.path, "w") as f:
                f.write(case)
            self.label = "<case>"
        else:
            raise TypeError("a case is a path, YAML text or a dict")

    def error(self, status, text):
        if self.label:
            text = text.replace(self.path, self.label)
        return CaseError(text or _STATUS.get(status, f"status {status}"), status)

    def close(self):
        if self.tmp:
            shutil.rmtree(self.tmp, ignore_errors=True)


def _call(kind, case, set, progress=None):
    import xarray as xr
    lib = _load()
    c = _Case(case)
    out_dir = tempfile.mkdtemp(prefix="rollsim_out_")
    out = os.path.join(out_dir, "out.nc")
    try:
        arr, n = _sets(set)
        msg = ctypes.create_string_buffer(4096)
        if progress is not None:
            errors = []

            def relay(_ctx, done, total):
                try:
                    progress(done, total)
                except Exception as e:  # noqa: BLE001 (reported after the call)
                    errors.append(e)

            cb = _PROGRESS(relay)
            status = lib.rs_api_sweep_progress(c.path.encode(), arr, n, out.encode(), cb, None,
                                               msg, len(msg))
            if errors:
                raise errors[0]
        else:
            fn = lib.rs_api_run if kind == "run" else lib.rs_api_sweep
            status = fn(c.path.encode(), arr, n, out.encode(), msg, len(msg))
        if status != 0 and (status not in (3, 4) or not os.path.exists(out)):
            raise c.error(status, msg.value.decode(errors="replace"))
        with xr.open_dataset(out) as ds:
            result = ds.load()
        if status != 0:  # solver failure or interruption with records kept: data and a warning
            import warnings
            warnings.warn(f"rollsim: {msg.value.decode(errors='replace')} "
                          f"(status {result.attrs.get('status')!r})")
        return result
    finally:
        c.close()
        shutil.rmtree(out_dir, ignore_errors=True)


def run(case, set=None):
    """rollsim run: the output file as an xarray.Dataset."""
    return _call("run", case, set)


def sweep(case, set=None, progress=None):
    """rollsim sweep (the case's sweep: block): the sweep file as an xarray.Dataset.
    progress(done, total), if given, is called after every point."""
    return _call("sweep", case, set, progress)


def _parse_value(text):
    import yaml
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError:
        return text


def check(case, set=None):
    """rollsim check: every resolved key and derived value as a dict {dotted key: value}."""
    lib = _load()
    c = _Case(case)
    try:
        arr, n = _sets(set)
        msg = ctypes.create_string_buffer(4096)
        text = ctypes.c_void_p()
        status = lib.rs_api_check(c.path.encode(), arr, n, ctypes.byref(text), msg, len(msg))
        out = ctypes.string_at(text).decode() if text.value else ""
        if text.value:
            lib.rs_api_free(text)
        if status != 0:
            raise c.error(status, msg.value.decode(errors="replace"))
    finally:
        c.close()
    values = {}
    for line in out.splitlines():
        if not line or line.startswith("#") or ": " not in line:
            continue
        key, _, rest = line.partition(": ")
        value = rest.split("  # ")[0].strip()
        values[key.strip()] = _parse_value(value)
    return values


def status(path):
    """rollsim status FILE.nc: how far a sweep file got, as a dict: state ("complete",
    "incomplete": interrupted, still being written, or its writer was killed and the status
    attribute still reads "running" (the summary says which, on the writer's host); "failed": points that did not converge; "not a sweep"), points, written,
    failed (ints; of the part in a part file), part, parts, status (the attribute),
    last_written (ISO 8601 UTC) and summary (the line rollsim status prints). An incomplete
    sweep is finished by rollsim sweep CASE.yaml -o FILE.nc --resume."""
    lib = _load()
    msg = ctypes.create_string_buffer(4096)
    text = ctypes.c_void_p()
    code = lib.rs_api_status(os.fspath(path).encode(), ctypes.byref(text), msg, len(msg))
    out = ctypes.string_at(text).decode() if text.value else ""
    if text.value:
        lib.rs_api_free(text)
    if code != 0:
        raise CaseError(msg.value.decode(errors="replace"), code)
    result = {}
    for line in out.splitlines():
        key, _, value = line.partition(": ")
        result[key] = int(value) if key in ("points", "written", "failed", "part", "parts") \
            else value
    return result
