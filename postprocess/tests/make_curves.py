"""Writes synthetic curve files (`vibromap continue --curve KIND ... -o F.h5`) with h5py, in the
layout vibromap_curves.py describes, for the tests of read_curves and of the map pictures'
--curves:

  root attributes  vibromap_file = "curves", scene, param, param2, param_unit, param2_unit,
                   Conventions = "CF-1.8", vibromap_version, command, then version and
                   attribute_checksum (stamp.py)
  /curve_i         attributes kind, stop, n; datasets over the dimension scale `point` (0..N-1):
                   param, param2, T_con, k_con, z_ratio, F_max (float64), stable (int8),
                   multipliers_re, multipliers_im (N x 4, second dimension the scale
                   `multiplier` 0..3), residual (float64)
  /curve_i/codim2  param, param2 (float64), kind (variable-length strings) over the dimension
                   scale `codim2` (0..M-1; M may be 0)
"""

from __future__ import annotations

import h5py
import numpy as np

from stamp import stamp


def curve(kind: str, param, param2, n: int = 1, stop: str = "left the box; left the box", codim2=()) -> dict:
    """A curve to write: its kind, points and codim-2 points [(param, param2, kind), ...]; the
    orbit's values are made up from the points (k_con = 10 + param2, T_con = 1 / k_con)."""
    param, param2 = np.asarray(param, dtype=np.float64), np.asarray(param2, dtype=np.float64)
    k_con = 10.0 + np.arange(param.size, dtype=np.float64)
    return dict(kind=kind, stop=stop, n=n, param=param, param2=param2, k_con=k_con, T_con=1.0 / k_con,
                z_ratio=np.full(param.size, 0.01), F_max=1e4 * k_con, stable=(np.arange(param.size) % 2).astype(np.int8),
                residual=np.full(param.size, 1e-11), codim2=list(codim2))  # fmt: skip


def _scale(group, name, length):
    scale = group.create_dataset(name, data=np.arange(length, dtype=np.int64))
    scale.make_scale(name)
    return scale


def _write_curve(group, c: dict) -> None:
    group.attrs["kind"] = c["kind"]
    group.attrs["stop"] = c["stop"]
    group.attrs["n"] = np.int64(c["n"])
    size = c["param"].size
    point = _scale(group, "point", size)
    multiplier = _scale(group, "multiplier", 4)
    columns = [group.create_dataset(name, data=c[name], dtype="f8")
               for name in ("param", "param2", "T_con", "k_con", "z_ratio", "F_max")]  # fmt: skip
    columns.append(group.create_dataset("stable", data=c["stable"], dtype="i1"))
    mu = np.outer(np.linspace(0.2, 0.9, size), [1.0, 0.5, 0.25, 0.125])
    for name, values in (("multipliers_re", mu), ("multipliers_im", 0.1 * mu)):
        d = group.create_dataset(name, data=values, dtype="f8")
        d.dims[0].attach_scale(point)
        d.dims[1].attach_scale(multiplier)
    columns.append(group.create_dataset("residual", data=c["residual"], dtype="f8"))
    for d in columns:
        d.dims[0].attach_scale(point)
    codim2 = group.create_group("codim2", track_order=True)
    index = _scale(codim2, "codim2", len(c["codim2"]))
    for position, name in ((0, "param"), (1, "param2")):
        d = codim2.create_dataset(name, data=np.array([p[position] for p in c["codim2"]], dtype=np.float64), dtype="f8")
        d.dims[0].attach_scale(index)
    names = np.array([p[2] for p in c["codim2"]], dtype=object)
    kinds = codim2.create_dataset("kind", shape=names.shape, dtype=h5py.string_dtype())
    if names.size:
        kinds[...] = names
    kinds.dims[0].attach_scale(index)


def write_curves(path, curves: list[dict], param: str = "contact.E1", param2: str = "contact.E2", units=("Pa", "Pa"),
                 attributes: dict | None = None) -> None:  # fmt: skip
    """Writes a curve file of `curves` (curve()) in the plane of param x param2, stamped; attributes:
    root attributes replacing or adding to the usual ones (None as a value: left out)."""
    root = dict(vibromap_file="curves", title="vibromap curves", Conventions="CF-1.8", vibromap_version="0.1.0",
                command="vibromap continue jobs/paper/table2.toml --curve fold", scene="[system]\nm1 = 1000.0\n",
                param=param, param2=param2, param_unit=units[0], param2_unit=units[1])  # fmt: skip
    root.update(attributes or {})
    with h5py.File(path, "w", track_order=True) as f:
        for name, value in root.items():
            if value is not None:
                f.attrs[name] = value
        for i, c in enumerate(curves):
            _write_curve(f.create_group(f"curve_{i}", track_order=True), c)
    stamp(path, "curve file")
