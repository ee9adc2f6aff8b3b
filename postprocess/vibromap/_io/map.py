"""Reading a map file (one file per sweep) into a SweepMap. Part of the readers that vibromap._io
gathers (import them from there).

Map file (include/vibromap/io/map_file.hpp; N axes, first axis slowest; format version
FORMAT_VERSIONS["regime map"], a map of another version is refused):
  /<axis>   1-D float64 coordinate of each swept parameter (E1, E2, R1, R2, m2, k2, omega2),
            a dimension scale with attributes units, long_name, key (the full scene key,
            "forcing.omega"), scale ("lin" | "log")
  /done (uint8), /status (int8), /regime (int8), /stable (int8), /soft (int8), /n, /k (int32),
            /wall_s, /steady_residual (float64) and the scene's stored quantities (hertz_valid
            always; T_con, k_con, ..., max_multiplier, lyapunov): N-D datasets with the axes
            attached as dimension scales, in order. regime, status, stable and soft carry CF
            flag_values/flag_meanings; -1 marks a cell not computed (done == 0), where float
            datasets hold NaN and integer ones 0. stable is 1 (stable), 0 (unstable) or -1
            (unknown: no periodic orbit, not computed); soft is 1 where the motion is periodic
            with impacts, stable, Hertz-valid and has k_con <= soft_kcon; a quantity whose long_name
            ends in "(NaN where not computed)" (max_multiplier, lyapunov) is NaN also in cells
            done where it was not computed.
  root attributes  title, Conventions, vibromap_version, scene, identity, ranks, cells_total,
            cells_done, complete, stored (the quantity names, space separated), census_attractors
            (A > 0 in a census map), steady ("follow": the motion the initial state settles into;
            "shooting": some stable periodic orbit found by Newton's method, not necessarily that
            motion; "integrate": brute-force integration), hertz_limit, soft_kcon, version,
            attribute_checksum; an adaptive map (sweep.refine) adds refine_levels, refine_on,
            refine_audit_fraction, refine_speckle and its figures, and the datasets computed and
            level; a map made with analysis.fragility > 0 adds the root attribute fragility (the
            perturbations' size, motion scales) and /fragile (int8: 1 where a perturbation of the
            initial state ends on another attractor, 0 where none does, -1 not assessed)
  census map (a sweep whose scene had [census]): /attractors (N-D int32), /soft_fraction,
            /unresolved_fraction, /unlisted_fraction, /budget_fraction (N-D float64), and per
            (cell, attractor) /attractor_<q> of shape + (A,) over the coordinate /attractor:
            regime, stable, hertz_valid, from_rest, soft, transient (int8, -1 beyond the cell's
            attractors), n, k, T_con, k_con, F_max, z_ratio, max_floquet, fraction,
            fraction_stderr, x1, x2, v1, v2 (NaN beyond the cell's attractors); the ordinary
            datasets describe the attractor the rest state reaches, and steady_residual is NaN there;
            /basin_entropy (N-D float64, -sum f ln f over the cell's outcomes) where vibromap
            wrote it (census maps made before it did lack it, and are read without it)
read_map() reads it (census datasets in SweepMap.census), and refuses a map that lacks any of
these (VibromapFileError naming what).
"""

from __future__ import annotations

import dataclasses
import os

import h5py
import numpy as np

from .h5io import VibromapFileError, _attribute_value, _flag_meanings, _text, open_h5, read_dataset
from .regimes import STEADY_ANSWERS, regime_labels

# Datasets every map has (map_file.hpp); the stored quantities (hertz_valid always) come on top.
MAP_REQUIRED = ("done", "status", "regime", "stable", "soft", "n", "k", "wall_s", "steady_residual")
# Root attributes every map has.
MAP_ATTRIBUTES = ("title", "Conventions", "vibromap_version", "scene", "identity", "ranks", "cells_total",
                  "cells_done", "complete", "stored", "census_attractors", "steady", "hertz_limit", "soft_kcon")
# A census map's families per (cell, attractor), kept in SweepMap.census under these names.
FAMILY_DATASETS = ("family", "family_flags")
FAMILY_LABEL_CHANGE, FAMILY_EDGE = 1, 2  # bits of family_flags


def census_regimes(sweep, mask) -> str:
    """The regimes of a census map's (cell, attractor) entries under `mask`, each once in order of
    appearance: "(1,1) no-contact"."""
    seen = []
    for r, n, k in zip(sweep.census["regime"][mask], sweep.census["n"][mask], sweep.census["k"][mask]):
        name = sweep.regime_meanings.get(int(r), str(r))
        text = f"({n},{k})" if name == "periodic" else name.replace("_", "-")
        if text not in seen:
            seen.append(text)
    return " ".join(seen)

# A census map's datasets (census_attractors > 0): per cell, then per (cell, attractor) without
# their prefix attractor_.
CENSUS_CELL = ("attractors", "soft_fraction", "unresolved_fraction", "unlisted_fraction", "budget_fraction")
CENSUS_ATTRACTOR = ("regime", "stable", "hertz_valid", "from_rest", "soft", "transient", "n", "k", "T_con", "k_con",
                    "F_max", "z_ratio", "max_floquet", "fraction", "fraction_stderr", "x1", "x2", "v1", "v2")
# An adaptive map's root attributes (refine_levels > 0) and datasets.
REFINE_ATTRIBUTES = ("refine_on", "refine_audit_fraction", "refine_speckle", "refine_solved_per_level",
                     "refine_solved", "refine_inherited", "refine_audited", "refine_mismatches",
                     "refine_mismatch_bound", "refine_whole_blocks")
REFINE_DATASETS = ("computed", "level")
# How a quantity's long_name says that NaN in a cell done means "not computed there" (the C++
# quantity table's descriptions, core/quantities.hpp): the file, not a list here, names them.
NOT_COMPUTED_NOTE = "(NaN where not computed)"


@dataclasses.dataclass
class MapAxis:
    """One swept parameter of a map: its grid values (SI units) and how they were spaced."""

    name: str  # the coordinate's name: the scene key within its section (E1, omega, F0, ...)
    values: np.ndarray  # 1-D float64, the grid points
    scale: str  # "lin" or "log" (plots use a log axis for "log")
    units: str  # e.g. "Pa"
    long_name: str  # e.g. "Young's modulus of body 1"
    key: str  # the full scene key, e.g. "forcing.omega"
    # A categorical axis (contact.law): every choice's name; values are indices into it (the
    # coordinate's CF flag_meanings). Empty for a numeric axis.
    categories: list[str] = dataclasses.field(default_factory=list)

    @property
    def is_log(self) -> bool:
        return self.scale == "log" and not self.categories

    @property
    def plot_values(self) -> np.ndarray:
        """Where the grid points sit on a plot: the values, or 0, 1, ... for a categorical axis
        (whose values are indices in any order)."""
        if self.categories:
            return np.arange(self.values.size, dtype=np.float64)
        return np.asarray(self.values, dtype=np.float64)

    def tick_labels(self) -> list[str]:
        """The category name of each grid point of a categorical axis."""
        return [self.categories[int(v)] if 0 <= int(v) < len(self.categories) else str(v) for v in self.values]

    def label(self) -> str:
        """Axis label for a plot, e.g. "E1 (Young's modulus of body 1), Pa"."""
        text = self.name if not self.long_name or self.long_name == self.name else f"{self.name} ({self.long_name})"
        return f"{text}, {self.units}" if self.units and self.units != "1" else text


@dataclasses.dataclass
class SweepMap:
    """A regime map as read from a map file: axes in file order, N-D arrays in axis order."""

    path: str
    axes: dict[str, MapAxis]  # in file order (first axis slowest)
    data: dict[str, np.ndarray]  # dataset name -> N-D array of shape `shape`
    units: dict[str, str]  # dataset name -> units attribute ("" when none)
    attrs: dict  # root attributes: str, int, float or numpy arrays
    stored: list[str]  # the optional quantities the scene stored (T_con, k_con, ...)
    regime_meanings: dict[int, str]  # regime code -> meaning as in the file ("no_contact")
    status_meanings: dict[int, str]  # status code -> meaning ("ok", "budget", ...)
    stable_meanings: dict[int, str]  # stable code -> meaning ("unknown", "unstable", "stable")
    census: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    # census maps: "regime", "n", "k_con", "fraction", ... (attractor_<q> without its prefix),
    # each of shape + (A,); empty in a map without a census
    long_names: dict[str, str] = dataclasses.field(default_factory=dict)  # dataset name -> long_name ("" when none)

    @property
    def is_census(self) -> bool:
        return bool(self.census)

    @property
    def hertz_limit(self) -> float:
        """z_max/R* above which Hertz theory does not hold (the map's analysis.hertz_limit)."""
        return float(self.attrs["hertz_limit"])

    @property
    def soft_kcon(self) -> float:
        """The largest k_con of a soft motion (the map's analysis.soft_kcon)."""
        return float(self.attrs["soft_kcon"])

    @property
    def steady(self) -> str:
        """How the cells' motions were found: "follow", "shooting" or "integrate"."""
        return str(self.attrs["steady"])

    def answer_text(self) -> str:
        """What each cell's answer is, e.g. "some stable orbit (shooting), not necessarily the motion
        from rest"."""
        return STEADY_ANSWERS.get(self.steady, f"steady = {self.steady}")

    def answer_warning(self) -> str:
        """The line every picture of a shooting map carries ("" for any other map): its cells are
        not necessarily the motion from rest, so a soft cell may not be reached from it."""
        return f"answer: {STEADY_ANSWERS['shooting']}" if self.steady == "shooting" else ""

    @property
    def fragility(self) -> float:
        """The size of the perturbations the map's cells were assessed with (analysis.fragility,
        motion scales); 0 when the map was made without."""
        return float(self.attrs.get("fragility", 0.0))

    def fragile_cells(self) -> np.ndarray | None:
        """True where the cell is fragile (a perturbation of its initial state ends on another
        attractor: its label is not an answer); None for a map made without analysis.fragility."""
        if "fragile" not in self.data:
            return None
        return np.asarray(self.data["fragile"]) == 1

    def refine_note(self) -> str:
        """The two lines every picture of an adaptive map (sweep.refine > 0) carries ("" for any other
        map): how many points were solved, on which quantities, and that the others are inherited,
        so that a class the map was not refined on is not read at the fine resolution."""
        if "refine_levels" not in self.attrs:
            return ""
        computed = np.asarray(self.data["computed"])
        solved, audited = int(np.count_nonzero(computed == 1)), int(np.count_nonzero(computed == 2))
        on = _text(self.attrs.get("refine_on", "")).replace(" ", ", ")
        return (f"adaptive: {solved} of {computed.size} points solved ({100.0 * solved / computed.size:.3g} %), "
                f"{audited} audited,\nrefined where {on or 'the refine quantities'} change; the rest inherited")

    def not_computed_as_nan(self) -> list[str]:
        """The float datasets whose NaN in a cell done means "not computed there" (max_multiplier,
        lyapunov, ...): those whose long_name says so (NOT_COMPUTED_NOTE)."""
        return [name for name, text in self.long_names.items() if text.endswith(NOT_COMPUTED_NOTE)]

    @property
    def axis_names(self) -> list[str]:
        return list(self.axes)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(axis.values) for axis in self.axes.values())

    @property
    def ndim(self) -> int:
        return len(self.axes)

    def labels(self) -> np.ndarray:
        """regime_labels of every cell of the map (N-D array of str)."""
        return regime_labels(self.data["regime"], self.data["n"], self.data["k"], self.regime_meanings, self.data["done"])


def _map_axes(f: h5py.File, path: str) -> dict[str, MapAxis]:
    """The axes of a map: the dimension scales attached to /done, in order."""
    done = f["done"]
    axes: dict[str, MapAxis] = {}
    for i in range(done.ndim):
        scales = done.dims[i]
        if len(scales) == 0:
            raise VibromapFileError(f"{path}: not a vibromap map file (no axis attached to dimension {i} of 'done')")
        scale = scales[0]
        name = scale.name.rsplit("/", 1)[-1]
        if scale.ndim != 1 or scale.dtype.kind not in "iuf" or scale.shape[0] != done.shape[i]:
            raise VibromapFileError(f"{path}: axis '{name}' is not a 1-D numeric array of length {done.shape[i]}")
        if name in axes:
            raise VibromapFileError(f"{path}: axis '{name}' is attached to two dimensions of 'done'")
        for attribute in ("scale", "units", "long_name", "key"):
            if attribute not in scale.attrs:
                raise VibromapFileError(f"{path}: axis '{name}' has no attribute '{attribute}'")
        spacing = _text(scale.attrs["scale"])
        if spacing not in ("lin", "log"):
            raise VibromapFileError(f"{path}: axis '{name}' has scale '{spacing}' (expected lin or log)")
        axes[name] = MapAxis(
            name=name,
            values=np.asarray(read_dataset(scale, path), dtype=np.float64),
            scale=spacing,
            units=_text(scale.attrs["units"]),
            long_name=_text(scale.attrs["long_name"]),
            key=_text(scale.attrs["key"]),
            categories=_text(scale.attrs.get("flag_meanings", "")).split(),
        )
    return axes


def axis_name(sweep: "SweepMap", name: str | None) -> str | None:
    """The map's name of an axis given by its name (omega) or its full scene key (forcing.omega)."""
    if name is None or name in sweep.axes:
        return name
    for axis in sweep.axes.values():
        if axis.key and axis.key == name:
            return axis.name
    return name


def _check_layout(f: h5py.File, path: str) -> None:
    """Refuses a map that lacks a dataset or a root attribute every map of its kind has (plain,
    census, adaptive): VibromapFileError naming the first one missing."""
    for name in MAP_ATTRIBUTES:
        if name not in f.attrs:
            raise VibromapFileError(f"{path}: not a vibromap map file (no root attribute '{name}')")
    required = list(MAP_REQUIRED) + _text(f.attrs["stored"]).split()
    if int(np.asarray(f.attrs["census_attractors"]).reshape(())) > 0:
        required += list(CENSUS_CELL) + [f"attractor_{name}" for name in CENSUS_ATTRACTOR]
    if "fragility" in f.attrs:
        required.append("fragile")
    if "refine_levels" in f.attrs:
        required += list(REFINE_DATASETS)
        for name in REFINE_ATTRIBUTES:
            if name not in f.attrs:
                raise VibromapFileError(f"{path}: not a vibromap map file (an adaptive map without root attribute "
                                        f"'{name}')")
    for name in required:
        if not isinstance(f.get(name), h5py.Dataset):
            raise VibromapFileError(f"{path}: not a vibromap map file (no dataset '{name}')")
    if "hertz_valid" not in required:
        raise VibromapFileError(f"{path}: not a vibromap map file (its attribute 'stored' lacks hertz_valid)")


def _read_cells(f: h5py.File, path: str, axes: dict[str, MapAxis]):
    """(data, units, long_names, census): every N-D dataset of the map's shape by name, its units
    and long_name, and the census's per (cell, attractor) ones without their prefix attractor_."""
    shape = f["done"].shape
    data: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}
    long_names: dict[str, str] = {}
    census: dict[str, np.ndarray] = {}
    for name, item in f.items():
        if name in axes or not isinstance(item, h5py.Dataset) or item.dtype.kind not in "iufb":
            continue
        if item.shape != shape:
            if name in MAP_REQUIRED:
                raise VibromapFileError(f"{path}: dataset '{name}' has shape {item.shape}, not the map's {shape}")
            if (name.startswith("attractor_") or name in FAMILY_DATASETS) and item.shape[:-1] == shape:
                census[name.removeprefix("attractor_")] = read_dataset(item, path)
            continue
        data[name] = read_dataset(item, path)
        units[name] = _text(item.attrs.get("units", ""))
        long_names[name] = _text(item.attrs.get("long_name", ""))
    return data, units, long_names, census


def read_map(path: str) -> SweepMap:
    """Reads a map file written by vibromap (see the module docstring for the layout)."""
    path = os.fspath(path)
    with open_h5(path, "regime map") as f:
        _check_layout(f, path)
        if len(f["done"].shape) == 0:
            raise VibromapFileError(f"{path}: not a vibromap map file (dataset 'done' is a scalar)")
        axes = _map_axes(f, path)
        data, units, long_names, census = _read_cells(f, path, axes)
        meanings = {name: _flag_meanings(f[name], path) for name in ("regime", "status", "stable")}
        attrs = {name: _attribute_value(value) for name, value in f.attrs.items()}
    _check_soft_attributes(attrs, path)
    _check_progress_attributes(attrs, path)
    stored = str(attrs["stored"]).split()
    missing = [name for name in stored if name not in data]
    if missing:
        raise VibromapFileError(f"{path}: attribute 'stored' names '{missing[0]}', but there is no such dataset")
    return SweepMap(
        path=path,
        axes=axes,
        data=data,
        units=units,
        attrs=attrs,
        stored=stored,
        regime_meanings=meanings["regime"],
        status_meanings=meanings["status"],
        stable_meanings=meanings["stable"],
        census=census,
        long_names=long_names,
    )


def _check_progress_attributes(attrs: dict, path: str) -> None:
    """cells_done, complete and ranks, which the attribute checksum does not cover (a run rewrites
    them when it ends; /done is what counts), must at least be in range."""
    total = attrs["cells_total"]
    limits = {"cells_done": (0, total if isinstance(total, int) else None), "complete": (0, 1), "ranks": (1, None)}
    for name, (low, high) in limits.items():
        value = attrs[name]
        if isinstance(value, bool) or not isinstance(value, int) or value < low or (high is not None and value > high):
            allowed = f"{low}..{high}" if high is not None else f">= {low}"
            raise VibromapFileError(f"{path}: damaged: root attribute '{name}' is {value!r}, outside {allowed}")


def _check_soft_attributes(attrs: dict, path: str) -> None:
    """soft_kcon and hertz_limit must be positive numbers; steady a string."""
    for name in ("soft_kcon", "hertz_limit"):
        value = attrs[name]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (np.isfinite(value) and value > 0):
            raise VibromapFileError(f"{path}: root attribute '{name}' is not a positive number ({value!r})")
    if not isinstance(attrs["steady"], str):
        raise VibromapFileError(f"{path}: root attribute 'steady' is not a string")
