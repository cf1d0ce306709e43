"""Wheel and rail profiles of a case's profiles: block (docs/case-file.md "Wheel-rail
profiles"), read for drawing: the same formats and options as rollsim's reader
(src/io/profile.c), without its checks -- `rollsim check CASE` validates the files.

Coordinates as the files give them: y lateral toward the track centre, z downward, mm.
"""
import math
import os

import numpy as np

from . import PostError

SIMPACK = (".prr", ".prw")
MINIPROF = (".ban", ".whl")


def _numbers(text, path, lineno):
    try:
        return [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise PostError(f"{path}:{lineno}: expected numbers, got {text.strip()[:40]!r} "
                        "(rollsim check CASE names what is wrong)") from None


def read_points(path):
    """The points (y, z) in mm as the file lists them (SIMPACK: units.len.f applied)."""
    ext = os.path.splitext(path)[1].lower()
    try:
        lines = open(path, errors="replace").read().splitlines()
    except OSError as e:
        raise PostError(f"cannot open {path}: {e.strerror or e}") from None
    pts = []
    if ext in SIMPACK:
        unit, inside = 1.0, False
        for i, raw in enumerate(lines, 1):
            s = raw.split("!")[0].strip()
            if s == "point.begin":
                inside = True
            elif s == "point.end":
                break
            elif inside and s:
                pts.append([v * unit for v in _numbers(s, path, i)[:2]])
            elif s.startswith("units.len.f") and "=" in s:
                unit = 1000.0 / float(s.split("=", 1)[1])
    elif ext in MINIPROF:
        header = True
        for i, raw in enumerate(lines, 1):
            s = raw.strip()
            if header:
                header = bool(s)
                continue
            s = s.lstrip('"').strip()
            if s:
                pts.append(_numbers(s, path, i)[:2])
    else:
        for i, raw in enumerate(lines, 1):
            s = raw.split("#")[0].strip()
            if s:
                pts.append(_numbers(s, path, i)[:2])
    if len(pts) < 2:
        raise PostError(f"{path}: no profile points")
    return np.array(pts, dtype=np.float64)


def smooth(y, z, length):
    """Moving least squares as rollsim does it: a quadratic fitted with weights
    exp(-(d/length)^2) over +-3 length, z(y) for a monotone profile, else y(s), z(s) along
    the chord length."""
    monotone = bool(np.all(np.diff(y) > 0))
    t = y.copy() if monotone else np.concatenate(([0.0], np.cumsum(np.hypot(np.diff(y),
                                                                            np.diff(z)))))
    ny, nz = y.copy(), z.copy()
    for i in range(len(t)):
        sel = np.abs(t - t[i]) <= 3.0 * length
        if sel.sum() < 3:
            continue
        u = (t[sel] - t[i]) / length
        w = np.sqrt(np.exp(-u * u))
        basis = np.stack([np.ones_like(u), u, u * u], axis=1) * w[:, None]
        nz[i] = np.linalg.lstsq(basis, z[sel] * w, rcond=None)[0][0]
        if not monotone:
            ny[i] = np.linalg.lstsq(basis, y[sel] * w, rcond=None)[0][0]
    return ny, nz


def read_case(case_path):
    """The profiles: block of a case: {'rail': (y, z) or None, 'wheel': ..., options}."""
    import yaml
    try:
        with open(case_path) as f:
            doc = yaml.safe_load(f)
    except OSError as e:
        raise PostError(f"cannot open {case_path}: {e.strerror or e}") from None
    except yaml.YAMLError as e:
        raise PostError(f"{case_path}: not YAML: {e}") from None
    block = (doc or {}).get("profiles") if isinstance(doc, dict) else None
    if not isinstance(block, dict):
        raise PostError(f"{case_path}: no profiles: block")
    folder = os.path.dirname(case_path)
    scale = float(block.get("scale") or 1.0)
    length = float(block.get("smoothing") or 0.0)
    incl = block.get("rail_inclination") or 0.0
    if isinstance(incl, str) and incl.startswith("1:"):
        incl = math.atan(1.0 / float(incl[2:]))
    out = {"rail_inclination": float(incl),
           "gauge_height": float(block.get("gauge_height", 14.0)),
           "title": (doc.get("title") if isinstance(doc, dict) else None) or ""}
    for side in ("rail", "wheel"):
        name = block.get(side)
        if not name:
            out[side] = None
            continue
        path = name if os.path.isabs(name) else os.path.join(folder, name)
        p = read_points(path)
        y = p[:, 0] * scale * (-1.0 if block.get(f"{side}_mirror") else 1.0)
        z = p[:, 1] * scale
        if y[-1] < y[0]:
            y, z = y[::-1].copy(), z[::-1].copy()
        if length > 0:
            y, z = smooth(y, z, length)
        out[side] = (y, z)
        out[f"{side}_file"] = path
    return out


def contact(case_path, rollsim):
    """The wheel-rail contact rollsim check computes for a case with profiles.vertical_load
    (docs/case-file.md "profiles:"): {'wheel_shift': mm, 'patches': [{'y', 'z', 'angle' (deg),
    'fn' (N), 'p_max' (N/mm^2)}, ...]}, or None when the case gives no vertical_load."""
    import re
    import subprocess
    try:
        out = subprocess.run([rollsim, "check", case_path], capture_output=True, text=True)
    except OSError as e:
        raise PostError(f"cannot run {rollsim}: {e.strerror or e}") from None
    if out.returncode != 0:
        raise PostError(f"{rollsim} check {case_path} failed: " + out.stderr.strip())
    m = re.search(r"^wheel_rail\.wheel_shift: (\S+)", out.stdout, re.M)
    if not m:
        return None
    patches = {}
    for k, key, value in re.findall(r"^wheel_rail\.patch(\d+)\.(\w+): (.*?)(?:  #|$)",
                                    out.stdout, re.M):
        patches.setdefault(int(k), {})[key] = [float(v) for v in
                                               re.findall(r"[-+]?[0-9.]+(?:[eE][-+]?\d+)?", value)]
    found = []
    for k in sorted(patches):
        q = patches[k]
        found.append({"y": q["rail_point"][0], "z": q["rail_point"][1],
                      "angle": q["contact_angle"][0], "fn": q["normal_force"][0],
                      "p_max": q.get("max_pressure", [0.0])[0]})
    return {"wheel_shift": float(m.group(1)), "patches": found}


def place_rail(y, z, theta):
    """The rail inclined by theta about its origin, its top sloping down toward the track
    centre (as rollsim check reports it)."""
    c, s = math.cos(theta), math.sin(theta)
    return y * c - z * s, y * s + z * c


def wheel_drop(rail, wheel):
    """The vertical shift of the wheel that makes it touch the rail (the smallest gap zero)
    where both are functions of y over a common range, and the y of that point; (0, None)
    otherwise."""
    (ry, rz), (wy, wz) = rail, wheel
    if not (np.all(np.diff(ry) > 0) and np.all(np.diff(wy) > 0)):
        return 0.0, None
    lo, hi = max(ry[0], wy[0]), min(ry[-1], wy[-1])
    if lo >= hi:
        return 0.0, None
    ys = np.union1d(ry[(ry >= lo) & (ry <= hi)], wy[(wy >= lo) & (wy <= hi)])
    gap = np.interp(ys, ry, rz) - np.interp(ys, wy, wz)
    k = int(np.argmin(gap))
    return float(gap[k]), float(ys[k])


def read_sweep(path):
    """A sweep file on profiles (docs/file-format.md "Wheel-rail sweep files"): its variables
    as arrays (NaN where a position has no such patch), title and status."""
    import netCDF4
    try:
        nc = netCDF4.Dataset(path)
    except (OSError, RuntimeError) as e:
        raise PostError(f"{path}: cannot read as netCDF: {e}") from None
    with nc:
        need = ("lateral_displacement", "patches", "rail_y", "contact_angle", "Fn", "Fx", "Fs",
                "Fy_track")
        missing = [v for v in need if v not in nc.variables]
        if missing:
            raise PostError(f"{path}: not a sweep file on profiles (no {', '.join(missing)}; "
                            "rollsim sweep on a case with profiles: writes one)")
        data = {k: np.ma.filled(nc.variables[k][:].astype(float), np.nan) for k in nc.variables}
        data["title"] = getattr(nc, "title", "")
        data["status"] = getattr(nc, "status", "")
    return data
