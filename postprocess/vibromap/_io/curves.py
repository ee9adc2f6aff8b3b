"""Reading a curve file of `vibromap continue --curve KIND ... -o F.h5`: curves of codimension-one
bifurcations (fold, period-doubling, neimark-sacker, grazing) and level curves (level:k_con=10)
followed in a plane of two scene keys. Part of the readers that vibromap._io gathers (import them
from there).

Curve file (HDF5, CF-1.8; include/vibromap/io/curve_file.hpp):
  root attributes  vibromap_file = "curves" (the file's kind), scene, param, param2 (the full
            scene keys of the plane, e.g. "forcing.omega", "forcing.F0"), param_unit,
            param2_unit ("" when none), version (FORMAT_VERSIONS["curve file"]; a file of another
            version is refused), Conventions, vibromap_version, attribute_checksum
  /curve_0, /curve_1, ...  one group per curve, in the order found; attributes kind ("fold",
            "period-doubling", "neimark-sacker", "grazing", "level:k_con=10"), stop (why it
            ended, one sentence per direction joined by "; "), n (period of the orbit, int);
            datasets over the dimension `point` (N, a dimension scale 0..N-1):
              param, param2 (float64)       the curve in the plane, ordered along the curve
              T_con, k_con, z_ratio, F_max (float64)  the orbit's values (NaN where no contact)
              stable (int8: 1 stable, 0 not)
              multipliers_re, multipliers_im (N x 4 float64, dimension `multiplier`)
              residual (float64)            |defining condition| at the point
  /curve_i/codim2  its codimension-two points (M may be 0): param, param2 (float64) and kind
            (variable-length strings: "cusp", "fold+level:k_con=10", "grazing+fold", ...)

read_curves() gives one dict per curve (see there); a file that is not a curve file, is of
another format version, or lacks any of the above, is a VibromapFileError with a one-line message
naming the file.
"""

from __future__ import annotations

import os
import re

import h5py
import numpy as np

from .h5io import VibromapFileError, _scalar, _text, open_h5, read_dataset

CURVE_FILE_KIND = "curves"  # the root attribute vibromap_file of a curve file
CURVE_KINDS = ("fold", "period-doubling", "neimark-sacker", "grazing")  # and "level:NAME=VALUE"
CURVE_VALUES = ("T_con", "k_con", "z_ratio", "F_max")  # the orbit's values along a curve (NaN when absent)
_CURVE_GROUP = re.compile(r"curve_(\d+)")


def _check_kind(f: h5py.File, path: str) -> None:
    """A curve file says vibromap_file = "curves" and names the keys of its plane."""
    what = "not a curve file of vibromap continue --curve"
    if "vibromap_file" not in f.attrs:
        raise VibromapFileError(f"{path}: {what} (no root attribute vibromap_file = \"curves\")")
    kind = _text(f.attrs["vibromap_file"])
    if kind != CURVE_FILE_KIND:
        raise VibromapFileError(f"{path}: {what} (it is a '{kind}' file)")
    for name in ("param", "param2"):
        if not _text(f.attrs.get(name, "")):
            raise VibromapFileError(f"{path}: {what} (no root attribute '{name}', the key of the plane's axis)")
    for name in ("param_unit", "param2_unit"):
        if name not in f.attrs:
            raise VibromapFileError(f"{path}: {what} (no root attribute '{name}')")


def _column(group: h5py.Group, name: str, path: str, length: int | None):
    """A 1-D numeric dataset of the group as float64."""
    where = f"{group.name.lstrip('/')}/{name}"
    dataset = group.get(name)
    if not isinstance(dataset, h5py.Dataset):
        raise VibromapFileError(f"{path}: {group.name.lstrip('/')} has no dataset '{name}'")
    if dataset.ndim != 1 or dataset.dtype.kind not in "iuf":
        raise VibromapFileError(f"{path}: dataset '{where}' is not a 1-D numeric array")
    values = np.asarray(read_dataset(dataset, path), dtype=np.float64)
    if length is not None and values.size != length:
        raise VibromapFileError(f"{path}: dataset '{where}' has {values.size} values, not the curve's {length}")
    return values


def _codim2(group: h5py.Group, path: str) -> list[dict]:
    """The codimension-two points of a curve: [{param, param2, kind}, ...] (the group codim2)."""
    points = group.get("codim2")
    if not isinstance(points, h5py.Group):
        raise VibromapFileError(f"{path}: {group.name.lstrip('/')} has no group 'codim2'")
    param = _column(points, "param", path, None)
    param2 = _column(points, "param2", path, param.size)
    kinds = points.get("kind")
    if not isinstance(kinds, h5py.Dataset) or kinds.ndim != 1 or kinds.shape[0] != param.size:
        raise VibromapFileError(f"{path}: {points.name.lstrip('/')}/kind is not {param.size} strings")
    names = [_text(k) for k in np.asarray(kinds[()]).ravel()]
    return [{"param": float(a), "param2": float(b), "kind": k} for a, b, k in zip(param, param2, names)]


def _curve(group: h5py.Group, path: str, names: tuple[str, str, str, str]) -> dict:
    """One curve group as read_curves' dict."""
    where = group.name.lstrip("/")
    kind = _text(group.attrs.get("kind", ""))
    if not kind:
        raise VibromapFileError(f"{path}: {where} has no attribute 'kind' (fold, period-doubling, ..., level:NAME=VALUE)")
    if "n" not in group.attrs:
        raise VibromapFileError(f"{path}: {where} has no attribute 'n' (the period of its orbit)")
    param = _column(group, "param", path, None)
    curve = {
        "kind": kind,
        "stop": _text(group.attrs.get("stop", "")),
        "n": _scalar(group.attrs["n"], path, f"{where}/n", int),
        "param_name": names[0],
        "param2_name": names[1],
        "param_unit": names[2],
        "param2_unit": names[3],
        "param": param,
        "param2": _column(group, "param2", path, param.size),
        "group": where,
    }
    for name in CURVE_VALUES + ("residual",):
        curve[name] = _column(group, name, path, param.size)
    curve["stable"] = _column(group, "stable", path, param.size).astype(np.int8)
    real, imag = group.get("multipliers_re"), group.get("multipliers_im")
    shape = (param.size, 4)
    if not (isinstance(real, h5py.Dataset) and isinstance(imag, h5py.Dataset) and real.shape == imag.shape == shape):
        raise VibromapFileError(f"{path}: {where} has no multipliers_re and multipliers_im of {param.size} x 4")
    curve["multipliers"] = read_dataset(real, path) + 1j * read_dataset(imag, path)
    curve["codim2"] = _codim2(group, path)
    return curve


def read_curves(path: str) -> list[dict]:
    """The curves of a curve file (see the module docstring), in the file's order: one dict each
    with kind, stop, n, param_name, param2_name (the plane's scene keys), param_unit,
    param2_unit, param, param2 (float64 arrays along the curve), T_con, k_con, z_ratio, F_max,
    residual (float64), stable (int8), multipliers (complex N x 4), group ("curve_0", ...) and
    codim2 (a list of {param, param2, kind})."""
    path = os.fspath(path)
    with open_h5(path, "curve file") as f:
        _check_kind(f, path)
        names = tuple(_text(f.attrs[name]) for name in ("param", "param2", "param_unit", "param2_unit"))
        groups = sorted((int(m.group(1)), name) for name in f if (m := _CURVE_GROUP.fullmatch(name)))
        curves = []
        for _, name in groups:
            if not isinstance(f[name], h5py.Group):
                raise VibromapFileError(f"{path}: {name} is not a group")
            curves.append(_curve(f[name], path, names))
    return curves
