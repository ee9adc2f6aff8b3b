"""Reading a map file (one file per sweep) into a SweepMap. Part of the readers that vibromap_h5
gathers (import them from there).

Map file (include/vibromap/io/map_file.hpp; N axes, first axis slowest):
  /<axis>   1-D float64 coordinate of each swept parameter (E1, E2, R1, R2, m2, k2, omega2),
            a dimension scale with attributes units, long_name, scale ("lin" | "log")
  /done (uint8), /status (int8), /regime (int8), /stable (int8), /n, /k (int32), /wall_s,
            /steady_residual (float64) and the scene's stored quantities (T_con, k_con, ...,
            max_multiplier, lyapunov): N-D datasets with the axes attached as dimension scales,
            in order. regime, status and stable carry CF flag_values/flag_meanings; -1 marks a
            cell not computed (done == 0), where float datasets hold NaN and integer ones 0.
            stable is 1 (stable), 0 (unstable) or -1 (unknown: no periodic orbit, not computed);
            a quantity whose long_name ends in "(NaN where not computed)" (max_multiplier,
            lyapunov) is NaN also in cells done where it was not computed.
  root attributes  title, Conventions, vibromap_version, scene, ranks, cells_total,
            cells_done, complete, stored (the quantity names, space separated),
            census_attractors (A > 0 in a census map)
  census map (a sweep whose scene had [census]): /attractors (N-D int32), /soft_fraction,
            /unresolved_fraction, /unlisted_fraction, /budget_fraction (N-D float64; budget_fraction
            absent from maps written before it was kept), and per (cell, attractor)
            /attractor_<q> of shape + (A,) over the coordinate /attractor: regime, stable,
            hertz_valid, from_rest, soft, transient (int8, -1 beyond the cell's attractors;
            transient absent from maps written before it was kept), n, k,
            T_con, k_con, F_max, z_ratio, max_floquet, fraction, fraction_stderr, x1, x2, v1, v2
            (NaN beyond the cell's attractors); the ordinary datasets describe the attractor the
            rest state reaches, and steady_residual is NaN there
  soft flag (maps written since the one definition of a soft motion; older maps lack all of it):
            /soft (N-D int8, flag_values -1 0 1, flag_meanings "not_computed no yes"): 1 where the
            motion is periodic with impacts, stable, Hertz-valid and has k_con <= soft_kcon;
            /hertz_valid (N-D int64 0/1: z_ratio <= hertz_limit) always, no longer only when stored;
            root attributes soft_kcon (default 10), hertz_limit (default 0.05) and steady ("follow":
            the motion the initial state settles into; "shooting": some stable periodic orbit found
            by Newton's method, not necessarily that motion; "integrate": brute-force integration).
            add_soft_cells() reads them, or computes them from regime, stable, hertz_valid (else
            z_ratio <= hertz_limit, 0.05 without the attribute) and k_con for an older map, or says
            why it cannot.
read_map() reads it (census datasets in SweepMap.census) (a map from before /stable was kept
reads as stable == -1 everywhere).
"""

from __future__ import annotations

import dataclasses
import os

import h5py
import numpy as np

from vibromap_h5io import VibromapFileError, _attribute_value, _flag_meanings, _text, open_h5, read_dataset
from vibromap_regimes import (HERTZ_LIMIT_DEFAULT, REGIME_FLAG_MEANINGS, REGIME_FLAG_VALUES, SOFT_KCON_DEFAULT,
                              STABLE_FLAG_MEANINGS, STABLE_FLAG_VALUES, STABLE_UNKNOWN, STATUS_FLAG_MEANINGS,
                              STATUS_FLAG_VALUES, STEADY_ANSWERS, regime_labels)  # fmt: skip

# Datasets every map has (map_file.hpp); the optional quantities come on top of these.
MAP_REQUIRED = ("done", "status", "regime", "n", "k")
MAP_ALWAYS = MAP_REQUIRED + ("stable", "soft", "wall_s", "steady_residual")
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
    key: str = ""  # the full scene key, e.g. "forcing.omega" ("" in maps written before it was kept)
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
    stable_meanings: dict[int, str] = dataclasses.field(
        default_factory=lambda: dict(zip(STABLE_FLAG_VALUES, STABLE_FLAG_MEANINGS.split()))
    )  # stable code -> meaning ("unknown", "unstable", "stable")
    census: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)
    # census maps: "regime", "n", "k_con", "fraction", ... (attractor_<q> without its prefix),
    # each of shape + (A,); empty in a map without a census
    filled: tuple[str, ...] = ()  # datasets the file lacks that read_map made up ("stable": unknown)
    sealed: bool = False  # its attributes were verified by their checksum (False: a map made before it had one)
    long_names: dict[str, str] = dataclasses.field(default_factory=dict)  # dataset name -> long_name ("" when none)

    @property
    def is_census(self) -> bool:
        return bool(self.census)

    @property
    def hertz_limit(self) -> float:
        """z_max/R* above which Hertz theory does not hold (the file's, else the old default)."""
        return float(self.attrs.get("hertz_limit", HERTZ_LIMIT_DEFAULT))

    @property
    def soft_kcon(self) -> float:
        """The largest k_con of a soft motion (the file's, else the old default)."""
        return float(self.attrs.get("soft_kcon", SOFT_KCON_DEFAULT))

    @property
    def steady(self) -> str:
        """How the cells' motions were found: "follow", "shooting", "integrate"; "" when not recorded."""
        return str(self.attrs.get("steady", ""))

    def answer_text(self) -> str:
        """What each cell's answer is, e.g. "some stable orbit (shooting), not necessarily the motion
        from rest"; "not recorded (...)" for a map written before the steady attribute."""
        if not self.steady:
            return "not recorded (map written before the steady attribute)"
        return STEADY_ANSWERS.get(self.steady, f"steady = {self.steady}")

    def answer_warning(self) -> str:
        """The line every picture of a shooting map carries ("" for any other map): its cells are
        not necessarily the motion from rest, so a soft cell may not be reached from it."""
        return f"answer: {STEADY_ANSWERS['shooting']}" if self.steady == "shooting" else ""

    def refine_note(self) -> str:
        """The two lines every picture of an adaptive map (sweep.refine > 0) carries ("" for any other
        map): how many points were solved, on which quantities, and that the others are inherited,
        so that a class the map was not refined on is not read at the fine resolution."""
        if "refine_levels" not in self.attrs or "computed" not in self.data:
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
        spacing = _text(scale.attrs.get("scale", "lin"))
        if spacing not in ("lin", "log"):
            raise VibromapFileError(f"{path}: axis '{name}' has scale '{spacing}' (expected lin or log)")
        axes[name] = MapAxis(
            name=name,
            values=np.asarray(read_dataset(scale, path), dtype=np.float64),
            scale=spacing,
            units=_text(scale.attrs.get("units", "")),
            long_name=_text(scale.attrs.get("long_name", "")),
            key=_text(scale.attrs.get("key", "")),
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


def read_map(path: str) -> SweepMap:
    """Reads a map file written by vibromap (see the module docstring for the layout)."""
    path = os.fspath(path)
    opened = open_h5(path)
    with opened as f:
        for name in MAP_REQUIRED:
            if not isinstance(f.get(name), h5py.Dataset):
                raise VibromapFileError(f"{path}: not a vibromap map file (no dataset '{name}')")
        shape = f["done"].shape
        if len(shape) == 0:
            raise VibromapFileError(f"{path}: not a vibromap map file (dataset 'done' is a scalar)")
        axes = _map_axes(f, path)
        data: dict[str, np.ndarray] = {}
        units: dict[str, str] = {}
        long_names: dict[str, str] = {}
        census: dict[str, np.ndarray] = {}
        for name, item in f.items():
            if name in axes or not isinstance(item, h5py.Dataset) or item.dtype.kind not in "iufb":
                continue
            if item.shape != shape:
                if name in MAP_ALWAYS:
                    raise VibromapFileError(f"{path}: dataset '{name}' has shape {item.shape}, not the map's {shape}")
                if name.startswith("attractor_") and item.shape[:-1] == shape:
                    census[name[len("attractor_"):]] = read_dataset(item, path)
                continue
            data[name] = read_dataset(item, path)
            units[name] = _text(item.attrs.get("units", ""))
            long_names[name] = _text(item.attrs.get("long_name", ""))
        regime_meanings = _flag_meanings(f["regime"], REGIME_FLAG_VALUES, REGIME_FLAG_MEANINGS, path)
        status_meanings = _flag_meanings(f["status"], STATUS_FLAG_VALUES, STATUS_FLAG_MEANINGS, path)
        filled = () if isinstance(f.get("stable"), h5py.Dataset) else ("stable",)
        if not filled:
            stable_meanings = _flag_meanings(f["stable"], STABLE_FLAG_VALUES, STABLE_FLAG_MEANINGS, path)
        else:  # written before stability was kept: unknown everywhere
            stable_meanings = dict(zip(STABLE_FLAG_VALUES, STABLE_FLAG_MEANINGS.split()))
            data["stable"] = np.full(shape, STABLE_UNKNOWN, dtype=np.int8)
            units["stable"] = ""
        attrs = {name: _attribute_value(value) for name, value in f.attrs.items()}
    _check_soft_attributes(attrs, path)
    _check_progress_attributes(attrs, path)
    if "stored" in attrs:
        stored = str(attrs["stored"]).split()
        missing = [name for name in stored if name not in data]
        if missing:
            raise VibromapFileError(f"{path}: attribute 'stored' names '{missing[0]}', but there is no such dataset")
    else:
        stored = [name for name in data if name not in MAP_ALWAYS]
    return SweepMap(
        path=path,
        axes=axes,
        data=data,
        units=units,
        attrs=attrs,
        stored=stored,
        regime_meanings=regime_meanings,
        status_meanings=status_meanings,
        stable_meanings=stable_meanings,
        census=census,
        filled=filled,
        sealed=opened.sealed,
        long_names=long_names,
    )


def _check_progress_attributes(attrs: dict, path: str) -> None:
    """cells_done, complete and ranks, which the attribute checksum does not cover (a run rewrites
    them when it ends; /done is what counts), must at least be in range."""
    total = attrs.get("cells_total")
    limits = {"cells_done": (0, total if isinstance(total, int) else None), "complete": (0, 1), "ranks": (1, None)}
    for name, (low, high) in limits.items():
        if name not in attrs:
            continue
        value = attrs[name]
        if isinstance(value, bool) or not isinstance(value, int) or value < low or (high is not None and value > high):
            allowed = f"{low}..{high}" if high is not None else f">= {low}"
            raise VibromapFileError(f"{path}: damaged: root attribute '{name}' is {value!r}, outside {allowed}")


def _check_soft_attributes(attrs: dict, path: str) -> None:
    """soft_kcon and hertz_limit, when present, must be positive numbers; steady a string."""
    for name in ("soft_kcon", "hertz_limit"):
        value = attrs.get(name, 1.0)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (np.isfinite(value) and value > 0):
            raise VibromapFileError(f"{path}: root attribute '{name}' is not a positive number ({value!r})")
    if not isinstance(attrs.get("steady", ""), str):
        raise VibromapFileError(f"{path}: root attribute 'steady' is not a string")
