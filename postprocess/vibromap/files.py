"""Every file vibromap writes, opened as an xarray Dataset: ``vibromap.files.open(path)``.

    >>> import vibromap.files
    >>> ds = vibromap.files.open("map.h5")
    >>> ds.attrs["vibromap_kind"], ds.regime_name.values[0, 0], ds.k_con.attrs["units"]
    ('regime map', '(1,1)', '1')

The kind is found from the file itself (docs/file-formats.md): a regime map (uniform, census,
adaptive), a trajectory, orbit-diagram, branch, curve, basins or optimisation file (HDF5), the
CSV of ``vibromap accuracy --csv`` or the JSON of ``vibromap restitution --format json``. The
Dataset's attribute ``vibromap_kind`` names it; its other attributes are the file's root ones.

Codes are decoded to names: every integer variable with CF ``flag_values``/``flag_meanings``
gets a string variable ``<name>_name`` beside it, of the same dimensions, holding each
element's meaning ("ok", "budget", "fold", "unlisted", ...); a regime gets its label instead,
"(n,k)" for a periodic one (from the ``n`` and ``k`` beside it), else "chatter", "no-contact",
..., and a map's cells not done are "not-computed". The codes stay as stored. Every variable
carries ``units`` and ``description`` (the file's ``long_name`` where it has no description).

Files of groups are gathered on their own dimensions: a curve file's curves along ``point``
(``point_curve`` says whose each point is; ``curve_kind``, ``curve_stop`` and ``curve_n`` along the
dimension ``curve``, the codimension-two points along ``codim2``); an optimisation file's
starts along ``evaluation`` (``evaluation_start``; the start's attributes along ``start``) and
its best points along ``best``. ``open(path, group="/starts/000")`` opens one group as stored.

A file that cannot be read raises :class:`DamagedFileError` (a ValueError) with the one line the
scripts of vibromap-post print: missing, not a vibromap file, of another format version, or
damaged. An HDF5 file is checked first in a forked child (its format version, attribute
checksum, and every dataset read), so that a file that crashes the HDF5 library raises that
error too instead of killing the interpreter.
"""

from __future__ import annotations

import builtins
import csv
import json
import os

import numpy as np

from ._guard import check_in_child
from ._io import (READ_ERRORS, VibromapFileError, _one_line, _text, open_h5, read_dataset, regime_labels)

# Root attribute title -> kind (FORMAT_VERSIONS' names); a trajectory file has no title.
TITLES = {
    "vibromap regime map": "regime map",
    "vibromap multistart optimisation": "optimisation file",
    "vibromap periodic-orbit branch": "branch file",
    "vibromap orbit diagram": "orbit-diagram file",
}
TITLE_PREFIXES = {"vibromap basins": "basins file", "vibromap curves": "curve file"}
ACCURACY_KIND, RESTITUTION_KIND = "accuracy CSV", "restitution JSON"
# The regime variables and the period and impact counts that name a periodic one.
REGIME_SIBLINGS = {"regime": ("n", "k"), "attractor_regime": ("attractor_n", "attractor_k"),
                   "attractor_shock_to_regime": (None, None)}  # fmt: skip


class DamagedFileError(VibromapFileError, ValueError):
    """A file vibromap.files cannot read: missing, not a vibromap file, of another format version
    or damaged. Its message is the one line the scripts print after "PROG: error: "."""


def open(path, group: str | None = None):  # noqa: A001 - vibromap.files.open, as the module's verb
    """The file at ``path`` as an xarray Dataset with its codes decoded (the module's docstring);
    ``group`` opens one group of an HDF5 file as stored. Raises DamagedFileError."""
    import xarray  # noqa: F401 - a clear ImportError before any work

    path = os.fspath(path)
    if not os.path.exists(path):
        raise DamagedFileError(f"{path}: no such file")
    if os.path.isdir(path):
        raise DamagedFileError(f"{path}: is a directory, not a file")
    if not _is_hdf5(path):
        return _open_text(path)
    ok, answer = check_in_child(_check_whole_file, path)
    if not ok:
        raise DamagedFileError(answer)
    kind = answer
    try:
        if group is not None:
            ds = _decode(_open_group(path, group))
        else:
            ds = OPENERS.get(kind, _open_plain)(path)
    except READ_ERRORS as exc:
        raise DamagedFileError(f"{path}: damaged or not a vibromap file: cannot read it ({exc})") from exc
    ds.attrs["vibromap_kind"] = kind
    ds.encoding["source"] = path  # where vibromap.plot reads it again
    return ds


def checked(path, kind: str | None = None) -> str:
    """The kind of the HDF5 file at ``path`` after the check open() makes in a forked child
    (version, checksum, every dataset read), checked as a file of ``kind`` when given;
    DamagedFileError when it fails or crashes."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise DamagedFileError(f"{path}: no such file")
    ok, answer = check_in_child(lambda p: _check_whole_file(p, kind), path)
    if not ok:
        raise DamagedFileError(answer)
    return answer


def kind_of(path) -> str:
    """The kind of vibromap file at ``path`` (the module's docstring), read in a forked child."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise DamagedFileError(f"{path}: no such file")
    if not _is_hdf5(path):
        return ACCURACY_KIND if _text_kind(path) == "csv" else RESTITUTION_KIND
    ok, answer = check_in_child(_root_kind, path)
    if not ok:
        raise DamagedFileError(answer)
    return answer


# ---- HDF5: the kind, the check, the Dataset ----------------------------------------------


def _is_hdf5(path: str) -> bool:
    import h5py

    try:
        return bool(h5py.is_hdf5(path))
    except OSError as exc:
        raise DamagedFileError(f"{path}: cannot open ({exc.strerror or exc})") from exc


def _root_kind(path: str) -> str:
    """The kind named by the root attributes (title; a trajectory file has none but T)."""
    try:
        return _title_kind(path)
    except READ_ERRORS as exc:
        if isinstance(exc, VibromapFileError):
            raise
        raise VibromapFileError(f"{path}: cannot open ({_one_line(exc)})") from exc


def _title_kind(path: str) -> str:
    import h5py

    with h5py.File(path, "r") as f:
        title = _text(f.attrs["title"]) if "title" in f.attrs else ""
        if title in TITLES:
            return TITLES[title]
        for prefix, kind in TITLE_PREFIXES.items():
            if title.startswith(prefix):
                return kind
        if "T" in f.attrs and "t" in f:
            return "trajectory file"
    raise VibromapFileError(f"{path}: not a file vibromap writes (its title is '{title}')" if title else
                            f"{path}: not a file vibromap writes (no root attribute 'title')")


def _check_whole_file(path: str, kind: str | None = None) -> str:
    """Run in a child: the file's kind (given, or found), after its version, checksum and every
    dataset are read."""
    import h5py

    kind = kind or _root_kind(path)
    with open_h5(path, kind) as f:
        datasets = []
        f.visititems(lambda name, item: datasets.append(item) if isinstance(item, h5py.Dataset) else None)
        for dataset in datasets:
            read_dataset(dataset, path)
    return kind


def _open_group(path: str, group: str | None):
    import xarray

    with xarray.open_dataset(path, engine="h5netcdf", group=group) as ds:
        return ds.load()


def _open_plain(path: str):
    return _decode(_open_group(path, None))


def _open_map(path: str):
    ds = _decode(_open_group(path, None))
    if "regime_name" in ds and "done" in ds:
        ds["regime_name"] = ds.regime_name.where(ds.done != 0, "not-computed")
    return ds


def _open_basins(path: str):
    """The plane's labels named by their attractor's regime (the negative codes by their flags)."""
    ds = _decode(_open_group(path, None))
    if "label" in ds and "regime_name" in ds:
        label = ds.label.values
        names = np.asarray(ds.regime_name.values, dtype=object)
        decoded = np.asarray(ds.label_name.values, dtype=object)
        listed = (label >= 0) & (label < len(names))
        decoded[listed] = names[label[listed]]
        ds["label_name"] = (ds.label.dims, decoded.astype(str), {"description": "the pixel's attractor's regime, "
                                                                               "or why it has none"})
    return ds


def _open_curves(path: str):
    """Every curve along one dimension point (point_curve: its curve), codim-2 points along codim2."""
    import h5py
    import xarray

    with h5py.File(path, "r") as f:
        names = sorted((n for n in f if n.startswith("curve_")), key=lambda n: int(n.split("_")[1]))
        root = {k: _attr(v) for k, v in f.attrs.items()}
        meta = [{k: _attr(v) for k, v in f[n].attrs.items()} for n in names]
        has_codim2 = [f"{n}/codim2" in f for n in names]
    curves = [_open_group(path, f"/{n}") for n in names]
    points = [c.drop_vars("point") for c in curves]
    ds = xarray.concat(points, dim="point", data_vars="all", coords="minimal") if points else xarray.Dataset()
    ds = ds.assign(point_curve=("point", np.concatenate([np.full(c.sizes["point"], i) for i, c in enumerate(curves)])
                          if curves else np.zeros(0, int), {"description": "the curve of the point (curve_i)"}))
    ds = ds.assign(curve_kind=("curve", [str(m.get("kind", "")) for m in meta], {"description": "the curve's kind"}),
                   curve_stop=("curve", [str(m.get("stop", "")) for m in meta], {"description": "why it ended"}),
                   curve_n=("curve", [int(m.get("n", 0)) for m in meta], {"description": "the orbit's period", "units": "1"}))
    codim2 = [(i, _open_group(path, f"/{n}/codim2")) for i, n in enumerate(names) if has_codim2[i]]
    codim2 = [(i, c) for i, c in codim2 if c.sizes.get("codim2", 0) > 0]
    if codim2:
        joined = xarray.concat([c.drop_vars("codim2").rename({v: f"codim2_{v}" for v in c.data_vars})
                                for _, c in codim2], dim="codim2")
        curve_of = np.concatenate([np.full(c.sizes["codim2"], i) for i, c in codim2])
        ds = ds.merge(joined).assign(codim2_curve=("codim2", curve_of, {"description": "the curve it lies on"}))
    ds.attrs = root  # the file's, not the first curve's
    return _decode(ds)


def _open_optimisation(path: str):
    """The root, every start's evaluations along evaluation, the best points along best."""
    import h5py
    import xarray

    ds = _decode(_open_group(path, None))
    with h5py.File(path, "r") as f:
        starts = sorted(f["starts"]) if "starts" in f else []
        start_attrs = [{k: _attr(v) for k, v in f[f"starts/{s}"].attrs.items()} for s in starts]
        best = sorted(f["best"]) if "best" in f else []
        best_attrs = [{k: _attr(v) for k, v in f[f"best/{b}"].attrs.items() if np.ndim(_attr(v)) == 0} for b in best]
        best_x = [np.asarray(f[f"best/{b}/x"][()]) for b in best]
    evaluations = [_open_group(path, f"/starts/{s}").drop_vars("evaluation", errors="ignore") for s in starts]
    if evaluations:
        joined = _decode(xarray.concat(evaluations, dim="evaluation"))
        start_of = np.concatenate([np.full(e.sizes["evaluation"], i) for i, e in enumerate(evaluations)])
        ds = ds.merge(joined.rename({v: f"evaluation_{v}" for v in joined.data_vars if v in ds}))
        ds = ds.assign(evaluation_start=("evaluation", start_of, {"description": "the start of the evaluation"}))
    ds = ds.assign(_table("start", start_attrs))
    ds = ds.assign(_table("best", best_attrs))
    if best_x:
        ds = ds.assign(best_x=(("best", "variable"), np.stack(best_x), {"description": "the best point"}))
    if "variables" in ds.attrs:
        ds = ds.assign_coords(variable_name=("variable", str(ds.attrs["variables"]).split(),
                                             {"description": "the free parameter"}))
    return ds


def _table(dim: str, rows: list[dict]) -> dict:
    """Attributes of groups as variables along dim, named dim_<attribute>."""
    names = [k for k in rows[0]] if rows else []
    return {f"{dim}_{k}": (dim, [r.get(k) for r in rows], {"description": f"the {dim}'s attribute {k}"})
            for k in names if all(np.ndim(r.get(k)) == 0 for r in rows)}


def _attr(value):
    if isinstance(value, (bytes, str)):
        return _text(value)
    array = np.asarray(value)
    return array.reshape(()).item() if array.size == 1 else array


OPENERS = {"regime map": _open_map, "basins file": _open_basins, "curve file": _open_curves,
           "optimisation file": _open_optimisation}  # fmt: skip


# ---- decoding the codes --------------------------------------------------------------------


def _decode(ds):
    """<name>_name beside every flagged variable and regime; description beside long_name."""
    for name in list(ds.data_vars) + list(ds.coords):
        var = ds[name]
        if "description" not in var.attrs and "long_name" in var.attrs:
            var.attrs["description"] = var.attrs["long_name"]
        if name in REGIME_SIBLINGS or name.endswith("_regime") and name in ds.data_vars:
            ds[f"{name}_name"] = (var.dims, _regime_names(ds, name), {"description": f"the regime named: {name}"})
        elif "flag_values" in var.attrs and "flag_meanings" in var.attrs and name in ds.data_vars:
            ds[f"{name}_name"] = (var.dims, _flag_names(var), {"description": f"the meaning of {name}'s code"})
    return ds


def _flag_names(var) -> np.ndarray:
    values = [int(v) for v in np.atleast_1d(var.attrs["flag_values"])]
    meanings = str(var.attrs["flag_meanings"]).split()
    table = dict(zip(values, meanings))
    codes = np.asarray(var.values)
    unique, inverse = np.unique(codes, return_inverse=True)
    names = np.array([table.get(int(c), f"code_{int(c)}") for c in unique.tolist()] or [""], dtype=str)
    return names[inverse.reshape(codes.shape)] if codes.size else np.zeros(codes.shape, dtype=str)


def _regime_names(ds, name: str) -> np.ndarray:
    n_name, k_name = REGIME_SIBLINGS.get(name, (name.replace("regime", "n"), name.replace("regime", "k")))
    regime = np.asarray(ds[name].values)
    n = ds[n_name].values if n_name in ds else np.zeros_like(regime)
    k = ds[k_name].values if k_name in ds else np.zeros_like(regime)
    if np.shape(n) != regime.shape:
        n, k = np.zeros_like(regime), np.zeros_like(regime)
    return regime_labels(regime, n, k)


# ---- text files: the accuracy CSV and the restitution JSON ---------------------------------


def _text_kind(path: str) -> str:
    with builtins.open(path, "rb") as f:
        head = f.read(64).lstrip()
    if head.startswith(b"[") or head.startswith(b"{"):
        return "json"
    if head.startswith(b"method,"):
        return "csv"
    raise DamagedFileError(f"{path}: not a file vibromap writes (neither HDF5, the accuracy CSV nor the restitution JSON)")


def _open_text(path: str):
    import xarray

    if _text_kind(path) == "csv":
        rows = _csv_rows(path)
        ds = xarray.Dataset({k: ("case", _column([r[k] for r in rows])) for k in (rows[0] if rows else {})})
        ds.attrs["vibromap_kind"] = ACCURACY_KIND
        return ds
    try:
        with builtins.open(path, encoding="utf-8") as f:
            rows = json.load(f)
        if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
            raise ValueError("not a list of objects")
    except (OSError, ValueError) as exc:
        raise DamagedFileError(f"{path}: not the JSON of vibromap restitution ({exc})") from exc
    keys = list(rows[0]) if rows else []
    ds = xarray.Dataset({k: ("row", _column([r.get(k) for r in rows])) for k in keys})
    ds.attrs["vibromap_kind"] = RESTITUTION_KIND
    return ds


def _csv_rows(path: str) -> list[dict]:
    with builtins.open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
    if any(None in r or None in r.values() for r in rows):
        raise DamagedFileError(f"{path}: a row has another number of columns than the header")
    return rows


def _column(values: list) -> np.ndarray:
    """Numbers as float64 where every value is one (empty: NaN), else strings."""
    try:
        return np.array([float("nan") if v in ("", None) else float(v) for v in values], dtype=float)
    except (TypeError, ValueError):
        return np.array(["" if v is None else str(v) for v in values], dtype=str)
