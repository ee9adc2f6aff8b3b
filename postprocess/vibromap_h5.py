"""Readers for the HDF5 files vibromap writes, shared by the postprocess/ scripts.

Every reader returns numpy arrays and plain Python numbers and strings, and raises
VibromapFileError with a one-line message (naming the file) when the file is missing,
is not HDF5, lacks what the reader needs, or is damaged: open_h5 checks the attribute checksum
vibromap writes into every file (vibromap_seal.py; "FILE: damaged: its attributes fail their
checksum (...)"), a chunk that fails its Fletcher32 checksum is named, and whatever else h5py
raises while reading a damaged or truncated file becomes one line too. Scripts turn that into
exit status 2. Files without the checksum (written before it) are read as before.

Trajectory file (src/io/trajectory_file.cpp, include/vibromap/io/trajectory_file.hpp):
  datasets  t (s), x1, x2 (m), v1, v2 (m/s), Fc, F (N): 1-D float64 of equal length,
            each with a `units` attribute; t is the time since the start of the kept window
  root attributes  T (s), regime ("(n,k)" or a kind such as "chatter"), n, k,
            T_con (s), k_con (-), scene (the scene's TOML text), vibromap_version

Map file (include/vibromap/io/map_file.hpp, one file per sweep; N axes, first axis slowest):
  /<axis>   1-D float64 coordinate of each swept parameter (E1, E2, R1, R2, m2, k2, omega2),
            a dimension scale with attributes units, long_name, scale ("lin" | "log")
  /done (uint8), /status (int8), /regime (int8), /stable (int8), /n, /k (int32), /wall_s,
            /steady_residual (float64) and the scene's stored quantities (T_con, k_con, ...,
            max_multiplier, lyapunov): N-D datasets with the axes attached as dimension scales,
            in order. regime, status and stable carry CF flag_values/flag_meanings; -1 marks a
            cell not computed (done == 0), where float datasets hold NaN and integer ones 0.
            stable is 1 (stable), 0 (unstable) or -1 (unknown: no periodic orbit, not computed);
            max_multiplier and lyapunov are NaN also in cells done where they were not computed.
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
read_map() reads it (census datasets in SweepMap.census) (a map from before /stable was kept reads as stable == -1 everywhere);
slice2d() takes a 2-D (or 1-D strip) slice for plotting;
regime_labels() names each cell's regime: "(n,k)", "chatter", "no-contact", "not-computed".
"""

from __future__ import annotations

import dataclasses
import itertools
import os

import h5py
import numpy as np

from vibromap_seal import DamagedAttributes, check_seal

TRAJECTORY_COLUMNS = ("t", "x1", "x2", "v1", "v2", "Fc", "F")
TRAJECTORY_ATTRIBUTES = ("T", "regime", "n", "k", "T_con", "k_con", "scene", "vibromap_version")


class VibromapFileError(Exception):
    """A vibromap file cannot be read: missing, not HDF5, or not of the expected layout."""


def write_plot(prog: str, make_figure, output: str, dpi: int, errors: tuple = (VibromapFileError,),
               notes: list[str] | None = None) -> int:  # fmt: skip
    """A plotting script's end: draws make_figure() into output and says so (exit status 0), or
    prints the one-line error of an unreadable input or unwritable output (2). `notes`, which
    make_figure may fill, are printed before the "wrote" line."""
    import sys

    try:
        save_figure(make_figure(), output, dpi)
    except errors as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 2
    for note in notes or []:
        print(f"{prog}: note: {note}")
    print(f"{prog}: wrote {output}")
    return 0


@dataclasses.dataclass
class Trajectory:
    """A kept trajectory of one parameter point (physical coordinates, SI units)."""

    path: str
    t: np.ndarray  # time since the start of the kept window, s
    x1: np.ndarray  # displacement of the main body, m
    x2: np.ndarray  # displacement of the attached body, m
    v1: np.ndarray  # velocity of the main body, m/s
    v2: np.ndarray  # velocity of the attached body, m/s
    Fc: np.ndarray  # contact force, N
    F: np.ndarray  # external force, N
    units: dict[str, str]  # dataset name -> units as stored in the file
    T: float  # forcing period, s
    regime: str  # "(n,k)" or a regime kind
    n: int  # period in forcing periods (0 when not periodic)
    k: int  # impacts in nT (0 when not periodic)
    T_con: float  # duration of the longest impact, s
    k_con: float  # T / T_con, -
    scene: str  # the scene text the point was solved from
    vibromap_version: str

    @property
    def phase(self) -> np.ndarray:
        """Time in forcing periods, t / T."""
        return self.t / self.T


def _text(value) -> str:
    """An HDF5 string attribute as str (h5py gives bytes for fixed-length strings, and keeps the
    bytes of an invalid UTF-8 one as surrogates, which could not be printed: replaced here)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return _text(value.reshape(()).item())
    return str(value).encode("utf-8", errors="surrogateescape").decode("utf-8", errors="replace")


def _scalar(value, path: str, name: str, kind):
    """A numeric scalar attribute as float or int."""
    array = np.asarray(value)
    if array.size != 1 or array.dtype.kind not in "iuf":
        raise VibromapFileError(f"{path}: attribute '{name}' is not a number")
    return kind(array.reshape(()).item())


# What reading a damaged or truncated HDF5 file raises from h5py and numpy (a missing or
# garbled object, a size or type that makes no sense): reported as one line, never a traceback.
READ_ERRORS = (OSError, LookupError, ValueError, TypeError, RuntimeError, ArithmeticError, MemoryError)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


class OpenFile:
    """open_h5's answer, for `with open_h5(path) as f:` (f is the h5py.File). `sealed` says
    whether the file's attribute checksum was verified (False: a file written before vibromap
    sealed its files). Leaving the block closes the file and turns what a damaged file raises
    there (READ_ERRORS) into VibromapFileError naming the file."""

    def __init__(self, file: h5py.File, path: str, sealed: bool):
        self.file, self.path, self.sealed = file, path, sealed

    def __enter__(self) -> h5py.File:
        return self.file

    def __exit__(self, kind, exc, traceback) -> bool:
        self.file.close()
        if isinstance(exc, READ_ERRORS) and not isinstance(exc, VibromapFileError):
            raise VibromapFileError(f"{self.path}: damaged or not a vibromap file: cannot read it ({_one_line(exc)})") from exc
        return False


def open_h5(path: str) -> OpenFile:
    """Opens an HDF5 file for reading and checks its attribute checksum when it has one
    (vibromap_seal.py), or raises VibromapFileError with a one-line reason."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise VibromapFileError(f"{path}: no such file")
    if os.path.isdir(path):
        raise VibromapFileError(f"{path}: is a directory, not a file")
    try:
        if not h5py.is_hdf5(path):
            raise VibromapFileError(f"{path}: not an HDF5 file")
        f = h5py.File(path, "r")
    except READ_ERRORS as exc:
        if isinstance(exc, VibromapFileError):
            raise
        raise VibromapFileError(f"{path}: cannot open ({_one_line(exc)})") from exc
    try:
        sealed = check_seal(f)
    except DamagedAttributes as exc:
        f.close()
        raise VibromapFileError(f"{path}: damaged: {exc}; make it again with vibromap --overwrite") from None
    return OpenFile(f, path, sealed)


def read_trajectory(path: str) -> Trajectory:
    """Reads a trajectory file written by vibromap (see the module docstring for the layout)."""
    path = os.fspath(path)
    with open_h5(path) as f:
        columns: dict[str, np.ndarray] = {}
        units: dict[str, str] = {}
        for name in TRAJECTORY_COLUMNS:
            dataset = f.get(name)
            if not isinstance(dataset, h5py.Dataset):
                raise VibromapFileError(f"{path}: not a vibromap trajectory file (no dataset '{name}')")
            if dataset.ndim != 1 or dataset.dtype.kind not in "iuf":
                raise VibromapFileError(f"{path}: dataset '{name}' is not a 1-D numeric array")
            columns[name] = np.asarray(dataset[()], dtype=np.float64)
            units[name] = _text(dataset.attrs.get("units", ""))
        lengths = {len(values) for values in columns.values()}
        if len(lengths) != 1:
            raise VibromapFileError(f"{path}: trajectory datasets differ in length")
        missing = [name for name in TRAJECTORY_ATTRIBUTES if name not in f.attrs]
        if missing:
            raise VibromapFileError(f"{path}: not a vibromap trajectory file (no attribute '{missing[0]}')")
        attrs = f.attrs
        return Trajectory(
            path=path,
            units=units,
            T=_scalar(attrs["T"], path, "T", float),
            regime=_text(attrs["regime"]),
            n=_scalar(attrs["n"], path, "n", int),
            k=_scalar(attrs["k"], path, "k", int),
            T_con=_scalar(attrs["T_con"], path, "T_con", float),
            k_con=_scalar(attrs["k_con"], path, "k_con", float),
            scene=_text(attrs["scene"]),
            vibromap_version=_text(attrs["vibromap_version"]),
            **columns,
        )


# ---- map files ------------------------------------------------------------------------------

# Datasets every map has (map_file.hpp); the optional quantities come on top of these.
MAP_REQUIRED = ("done", "status", "regime", "n", "k")
MAP_ALWAYS = MAP_REQUIRED + ("stable", "soft", "wall_s", "steady_residual")
# The regime and status flags as map_file.hpp lists them (RegimeKind / SolveStatus order, -1
# first); read_map prefers the file's own flag_values/flag_meanings and falls back to these.
REGIME_FLAG_VALUES = tuple(range(-1, 9))
REGIME_FLAG_MEANINGS = (
    "not_computed periodic chatter no_contact permanent_contact quasi_periodic chaotic non_periodic unresolved failed"
)
STATUS_FLAG_VALUES = tuple(range(-1, 4))
STATUS_FLAG_MEANINGS = "not_computed ok budget failed invalid_input"
STABLE_FLAG_VALUES = (-1, 0, 1)
STABLE_FLAG_MEANINGS = "unknown unstable stable"
STABLE_UNKNOWN, STABLE_NO, STABLE_YES = STABLE_FLAG_VALUES  # codes of the stable dataset
REGIME_PERIODIC = 0  # regime code whose label is "(n,k)"
NOT_COMPUTED = "not-computed"
# The soft flag and the Hertz validity of a cell (the map's /soft, add_soft_cells' derived ones).
FLAG_UNKNOWN, FLAG_NO, FLAG_YES = -1, 0, 1
# add_soft_cells' keys in SweepMap.data (so that slices carry them): 1 yes, 0 no, -1 not computed
# or unknown. Their own keys, so that the file's /soft stays as read.
SOFT_KEY, HERTZ_KEY = "soft_flag", "hertz_flag"
SOFT_FROM_MAP = "from the map's /soft"  # SoftInfo.soft_source when the map's own flag is used
# analysis.hertz_limit and analysis.soft_kcon as maps without the attributes were computed with.
HERTZ_LIMIT_DEFAULT = 0.05
SOFT_KCON_DEFAULT = 10.0
# What a cell's answer is, by the map's steady attribute (analysis.steady).
STEADY_ANSWERS = {
    "follow": "the motion the initial state settles into (follow)",
    "integrate": "the motion the initial state settles into, by brute-force integration (integrate)",
    "shooting": "some stable orbit (shooting), not necessarily the motion from rest",
}


class MapSliceError(ValueError):
    """A slice of a map cannot be taken: unknown axis name, an axis used twice, a bad value."""


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


@dataclasses.dataclass
class FixedValue:
    """An axis held at one grid value in a slice."""

    name: str
    index: int  # grid index used
    value: float  # grid value used, SI units
    units: str
    requested: float | None  # the value asked for (None: the middle index by default)

    def text(self) -> str:
        """e.g. "R1 = 2 m"."""
        units = f" {self.units}" if self.units and self.units != "1" else ""
        return f"{self.name} = {self.value:.4g}{units}"


@dataclasses.dataclass
class MapSlice:
    """A 2-D slice of a map (or a 1-D strip when y is None): arrays of shape (ny, nx), ny = 1
    for a strip, so that array[j, i] belongs to y.values[j], x.values[i]."""

    x: MapAxis
    y: MapAxis | None
    data: dict[str, np.ndarray]  # dataset name -> 2-D array (ny, nx)
    fixed: list[FixedValue]  # the other axes, in file order
    regime_meanings: dict[int, str]

    def labels(self) -> np.ndarray:
        """regime_labels of the slice's cells, shape (ny, nx)."""
        return regime_labels(self.data["regime"], self.data["n"], self.data["k"], self.regime_meanings, self.data["done"])

    def fixed_text(self) -> str:
        """The fixed axes, e.g. "R1 = 2 m, m2 = 310 kg" ("" when there are none)."""
        return ", ".join(value.text() for value in self.fixed)


def _flag_meanings(dataset: h5py.Dataset, default_values, default_meanings: str, path: str) -> dict[int, str]:
    """code -> meaning from a dataset's CF flag_values / flag_meanings (defaults if absent)."""
    values = dataset.attrs.get("flag_values", default_values)
    meanings = _text(dataset.attrs.get("flag_meanings", default_meanings)).split()
    values = [int(v) for v in np.asarray(values).ravel()]
    if len(values) != len(meanings):
        raise VibromapFileError(
            f"{path}: dataset '{dataset.name.lstrip('/')}' has {len(values)} flag_values but {len(meanings)} flag_meanings"
        )
    return dict(zip(values, meanings))


def _attribute_value(value):
    """A root attribute as str, int, float or (for arrays) a numpy array."""
    if isinstance(value, (bytes, str)):
        return _text(value)
    array = np.asarray(value)
    if array.dtype.kind in "SUO":
        return _text(value)
    if array.size == 1 and array.ndim <= 1:
        return array.reshape(()).item()
    return array


def _missing_chunk(dataset: h5py.Dataset):
    """The offset of a chunk missing from the chunk index of a dataset whose chunks are all made
    with it (a map's: HDF5 would read fill values there without an error); None when none is.
    Each chunk is looked up as a read looks it up (read_direct_chunk; get_chunk_info_by_coord
    does not compare the whole key, and can find a chunk that a read then misses)."""
    if dataset.chunks is None or dataset.id.get_create_plist().get_alloc_time() != h5py.h5d.ALLOC_TIME_EARLY:
        return None
    for offset in itertools.product(*(range(0, n, c) for n, c in zip(dataset.shape, dataset.chunks))):
        try:
            dataset.id.read_direct_chunk(offset)
        except READ_ERRORS:
            return offset
    return None


def read_dataset(dataset: h5py.Dataset, path: str) -> np.ndarray:
    """The whole dataset as a numpy array, or VibromapFileError naming it when a chunk of it fails
    to read (vibromap's maps checksum every chunk: a damaged byte fails instead of reading wrong)
    or is missing from its chunk index."""
    name = dataset.name.lstrip("/")
    try:
        missing = _missing_chunk(dataset)
    except READ_ERRORS as exc:
        raise VibromapFileError(f"{path}: dataset '{name}' is damaged: its chunk index cannot be read ({_one_line(exc)})") from exc
    if missing is not None:
        raise VibromapFileError(f"{path}: dataset '{name}' is damaged: its chunk at {tuple(int(i) for i in missing)} is "
                                "missing from its chunk index; vibromap sweep --resume recomputes the damaged cells")
    try:
        return np.asarray(dataset[()])
    except OSError as exc:
        name = dataset.name.lstrip("/")
        raise VibromapFileError(
            f"{path}: dataset '{name}' is damaged: a chunk of it fails its checksum or cannot be read ({exc}); "
            "vibromap sweep --resume recomputes the damaged cells"
        ) from exc


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


def regime_labels(regime, n, k, meanings: dict[int, str] | None = None, done=None) -> np.ndarray:
    """Names each cell's regime: "(n,k)" for a periodic one, else its flag meaning with '_'
    written '-' ("chatter", "no-contact", "not-computed"); an unknown code gives "regime-<code>".
    Cells with done == 0 (when done is given) are "not-computed" whatever their code."""
    if meanings is None:
        meanings = dict(zip(REGIME_FLAG_VALUES, REGIME_FLAG_MEANINGS.split()))
    regime = np.asarray(regime).astype(np.int64)
    periodic = regime == REGIME_PERIODIC
    n = np.where(periodic, np.broadcast_to(np.asarray(n), regime.shape), 0).astype(np.int64)
    k = np.where(periodic, np.broadcast_to(np.asarray(k), regime.shape), 0).astype(np.int64)
    # Name each distinct (code, n, k) once: maps have many cells but few regimes.
    keys = np.stack([regime.ravel(), n.ravel(), k.ravel()], axis=1)
    unique, inverse = np.unique(keys, axis=0, return_inverse=True)
    names = []
    for code, n_i, k_i in unique.tolist():
        if code == REGIME_PERIODIC and n_i > 0:
            names.append(f"({n_i},{k_i})")
        elif code in meanings:
            names.append(meanings[code].replace("_", "-"))
        else:
            names.append(f"regime-{code}")
    # NOT_COMPUTED in the table makes the str dtype wide enough for the done == 0 overwrite.
    labels = np.array(names + [NOT_COMPUTED], dtype=str)[inverse.reshape(-1)].reshape(regime.shape)
    if done is not None:
        labels[np.broadcast_to(np.asarray(done), regime.shape) == 0] = NOT_COMPUTED
    return labels


def _label_key(label: str, kind_order: dict[str, int]):
    """Sort key: periodic (n,k) by n then k, then the kinds in flag order, not-computed last."""
    if label.startswith("(") and label.endswith(")"):
        try:
            n, k = (int(part) for part in label[1:-1].split(","))
            return (0, n, k, "")
        except ValueError:
            pass
    if label == NOT_COMPUTED:
        return (3, 0, 0, label)
    if label in kind_order:
        return (1, kind_order[label], 0, label)
    return (2, 0, 0, label)


def regime_counts(labels) -> dict[str, int]:
    """label -> number of cells, in a fixed order: (n,k) by n then k, chatter, no-contact, ...
    (flag order), unknown labels, not-computed last."""
    kinds = [meaning.replace("_", "-") for meaning in REGIME_FLAG_MEANINGS.split()]
    kind_order = {kind: i for i, kind in enumerate(kinds)}
    unique, counts = np.unique(np.asarray(labels, dtype=str), return_counts=True)
    pairs = sorted(zip(unique.tolist(), counts.tolist()), key=lambda pair: _label_key(pair[0], kind_order))
    return {label: int(count) for label, count in pairs}


@dataclasses.dataclass
class SoftInfo:
    """What add_soft_cells found: the definition it used and where each flag came from."""

    soft_kcon: float
    hertz_limit: float
    soft_source: str  # SOFT_FROM_MAP, "computed from ...", or why it cannot be told
    hertz_source: str  # "from the map's hertz_valid", "from z_ratio <= 0.05", or why it cannot be told
    soft_known: bool
    hertz_known: bool
    overruled: int = 0  # cells the map's /soft calls soft though Hertz-invalid: not soft here

    def rule(self) -> str:
        """The one definition of soft, e.g. "stable periodic with impacts, Hertz-valid, k_con <= 10"."""
        return f"stable periodic with impacts, Hertz-valid, k_con <= {self.soft_kcon:g}"

    def definition(self) -> str:
        """The one definition, as legends name it: "soft: " and the rule."""
        return f"soft: {self.rule()}"

    def invalid_text(self) -> str:
        """e.g. "Hertz-invalid (z_max/R* > 0.05)", with the map's hertz_limit."""
        return f"Hertz-invalid (z_max/R* > {self.hertz_limit:g})"


def periodic_with_impacts(data: dict[str, np.ndarray]) -> np.ndarray:
    """Cells computed whose motion is periodic with k > 0 impacts per period."""
    return (np.asarray(data["done"]) != 0) & (np.asarray(data["regime"]) == REGIME_PERIODIC) & (np.asarray(data["k"]) > 0)


def impact_cells(data: dict[str, np.ndarray]) -> np.ndarray:
    """Cells computed with at least one impact: k_con > 0 where the map stores k_con, else
    z_ratio > 0, else periodic with impacts."""
    done = np.asarray(data["done"]) != 0
    for name in ("k_con", "z_ratio"):
        if name in data:
            values = np.asarray(data[name], dtype=np.float64)
            return done & np.isfinite(values) & (values > 0)
    return periodic_with_impacts(data)


def hertz_validity(sweep: SweepMap) -> tuple[np.ndarray | None, str]:
    """Each cell's Hertz validity as int8 (1 valid, 0 invalid: z_max/R* > hertz_limit, -1 not
    computed or z_ratio NaN) and where it came from: the map's hertz_valid, else z_ratio against
    the map's hertz_limit (0.05 in maps without it); (None, why) when the map holds neither."""
    done = np.asarray(sweep.data["done"]) != 0
    if "hertz_valid" in sweep.data:
        valid = np.asarray(sweep.data["hertz_valid"]) != 0
        return np.where(done, valid, FLAG_UNKNOWN).astype(np.int8), "from the map's hertz_valid"
    if "z_ratio" in sweep.data:
        z = np.asarray(sweep.data["z_ratio"], dtype=np.float64)
        flags = np.select([~done | np.isnan(z), z <= sweep.hertz_limit], [FLAG_UNKNOWN, FLAG_YES], FLAG_NO)
        return flags.astype(np.int8), f"from z_ratio <= {sweep.hertz_limit:g}"
    return None, "the map stores neither hertz_valid nor z_ratio"


def computed_soft(sweep: SweepMap, hertz: np.ndarray | None, soft_kcon: float) -> tuple[np.ndarray | None, str]:
    """The soft flag by the one definition (is_soft, regime.hpp), cell by cell: periodic with
    impacts, stable == 1 (unknown is not soft), Hertz-valid and 0 < k_con <= soft_kcon; -1 where
    not computed. (None, why) when the map lacks what it takes: no guessing."""
    lacking = [what for what, missing in (("k_con", "k_con" not in sweep.data), ("hertz_valid or z_ratio", hertz is None),
                                          ("stable (written before stability was kept)", "stable" in sweep.filled))
               if missing]  # fmt: skip
    if lacking:
        return None, "the map has no /soft, and no " + ", ".join(lacking) + " to compute it from"
    k_con = np.asarray(sweep.data["k_con"], dtype=np.float64)
    soft = (periodic_with_impacts(sweep.data) & (np.asarray(sweep.data["stable"]) == STABLE_YES) & (hertz == FLAG_YES)
            & (k_con > 0) & (k_con <= soft_kcon))  # fmt: skip
    done = np.asarray(sweep.data["done"]) != 0
    source = "hertz_valid" if "hertz_valid" in sweep.data else "z_ratio"
    return np.where(done, soft, FLAG_UNKNOWN).astype(np.int8), f"computed from regime, stable, {source} and k_con"


def add_soft_cells(sweep: SweepMap, soft_kcon: float | None = None) -> SoftInfo:
    """Puts each cell's soft flag (data[SOFT_KEY]) and Hertz validity (data[HERTZ_KEY]) into the
    map's data, so that its slices carry them, and says where they came from. The map's /soft is
    used when it has one and soft_kcon is the map's own (the default); else soft is computed from
    the other datasets (an older map, or another soft_kcon asked for). A cell the map calls soft
    but Hertz-invalid is not soft here: no picture presents an invalid answer as soft. A flag
    that cannot be told is left out of data, and SoftInfo says why."""
    kcon = sweep.soft_kcon if soft_kcon is None else float(soft_kcon)
    hertz, hertz_source = hertz_validity(sweep)
    if "soft" in sweep.data and kcon == sweep.soft_kcon:
        done = np.asarray(sweep.data["done"]) != 0
        soft, soft_source = np.where(done, sweep.data["soft"], FLAG_UNKNOWN).astype(np.int8), SOFT_FROM_MAP
    else:
        soft, soft_source = computed_soft(sweep, hertz, kcon)
    overruled = 0
    if hertz is not None:
        sweep.data[HERTZ_KEY] = hertz
        if soft is not None:
            wrong = (soft == FLAG_YES) & (hertz == FLAG_NO)
            overruled = int(wrong.sum())
            soft = np.where(wrong, FLAG_NO, soft).astype(np.int8)
    if soft is not None:
        sweep.data[SOFT_KEY] = soft
    return SoftInfo(soft_kcon=kcon, hertz_limit=sweep.hertz_limit, soft_source=soft_source, hertz_source=hertz_source,
                    soft_known=soft is not None, hertz_known=hertz is not None, overruled=overruled)  # fmt: skip


def cell_boundary(mask: np.ndarray, x_edges: np.ndarray, y_edges: np.ndarray) -> list[np.ndarray]:
    """The outline of the cells of `mask` (ny, nx) along their edges, as polylines (2, 2) in
    data units: every edge between a cell in the mask and one outside it (or the map's border),
    runs of such edges along one grid line joined. A point is inside the region exactly when a
    ray from it crosses these segments an odd number of times."""
    padded = np.pad(np.asarray(mask, dtype=bool), 1)
    segments = []
    vertical = padded[1:-1, 1:] != padded[1:-1, :-1]  # (ny, nx + 1): edge at x_edges[i] of row j
    for i in range(vertical.shape[1]):
        for j0, j1 in _runs(vertical[:, i]):
            segments.append(np.array([[x_edges[i], y_edges[j0]], [x_edges[i], y_edges[j1]]]))
    horizontal = padded[1:, 1:-1] != padded[:-1, 1:-1]  # (ny + 1, nx): edge at y_edges[j] of column i
    for j in range(horizontal.shape[0]):
        for i0, i1 in _runs(horizontal[j]):
            segments.append(np.array([[x_edges[i0], y_edges[j]], [x_edges[i1], y_edges[j]]]))
    return segments


def _runs(flags: np.ndarray) -> list[tuple[int, int]]:
    """(start, end) of each run of True in a 1-D bool array, end exclusive."""
    edges = np.diff(np.concatenate(([0], flags.astype(np.int8), [0])))
    return list(zip(np.nonzero(edges == 1)[0].tolist(), np.nonzero(edges == -1)[0].tolist()))


def _nearest_index(axis: MapAxis, value: float) -> int:
    """Index of the grid value nearest to `value` (in log10 for a log axis of positive values)."""
    values = axis.values
    if axis.is_log and value > 0 and np.all(values > 0):
        distance = np.abs(np.log10(values) - np.log10(value))
    else:
        distance = np.abs(values - value)
    return int(np.argmin(distance))


def slice2d(sweep: SweepMap, x: str, y: str | None = None, fixed: dict[str, float] | None = None) -> MapSlice:
    """The slice of `sweep` over axes x (columns) and y (rows; None for a 1-D strip), with every
    other axis held at the grid value nearest to fixed[name], or at its middle index (len // 2)
    when not given. Raises MapSliceError for unknown or repeated axis names."""
    x, y = axis_name(sweep, x), axis_name(sweep, y)
    fixed = {axis_name(sweep, name): value for name, value in (fixed or {}).items()}
    names = sweep.axis_names
    known = ", ".join(names)
    for role, name in (("x", x), ("y", y)):
        if name is not None and name not in sweep.axes:
            raise MapSliceError(f"{sweep.path}: no axis '{name}' for {role} (axes: {known})")
    if x == y:
        raise MapSliceError(f"{sweep.path}: axis '{x}' cannot be both x and y")
    for name, value in fixed.items():
        if name not in sweep.axes:
            raise MapSliceError(f"{sweep.path}: no axis '{name}' to fix (axes: {known})")
        if name in (x, y):
            raise MapSliceError(f"{sweep.path}: axis '{name}' is the {'x' if name == x else 'y'} axis and cannot be fixed")
        if not np.isfinite(value):
            raise MapSliceError(f"{sweep.path}: the value to fix '{name}' at is not finite")
    selection: list = []
    held: list[FixedValue] = []
    for name, axis in sweep.axes.items():
        if name in (x, y):
            selection.append(slice(None))
            continue
        requested = fixed.get(name)
        index = len(axis.values) // 2 if requested is None else _nearest_index(axis, float(requested))
        selection.append(index)
        held.append(FixedValue(name, index, float(axis.values[index]), axis.units, requested))
    transpose = y is not None and names.index(x) < names.index(y)
    data = {}
    for name, array in sweep.data.items():
        part = array[tuple(selection)]
        data[name] = part.T if transpose else (part if y is not None else part.reshape(1, -1))
    return MapSlice(
        x=sweep.axes[x],
        y=sweep.axes[y] if y is not None else None,
        data=data,
        fixed=held,
        regime_meanings=sweep.regime_meanings,
    )


def cell_edges(axis: MapAxis) -> np.ndarray:
    """Cell edges around the grid values for pcolormesh: midpoints between neighbours, the ends
    half a spacing out; computed in log10 for a log axis, so the cells are even on a log plot.
    A one-point axis gets a cell of relative width 1 (a factor 10 on a log axis)."""
    values = axis.plot_values
    log = axis.is_log and np.all(values > 0)
    u = np.log10(values) if log else values.astype(np.float64)
    if u.size == 1:
        half = 0.5 if log or u[0] == 0 else 0.5 * abs(u[0])
        edges = np.array([u[0] - half, u[0] + half])
    else:
        mid = 0.5 * (u[1:] + u[:-1])
        edges = np.concatenate(([u[0] - (mid[0] - u[0])], mid, [u[-1] + (u[-1] - mid[-1])]))
    return 10.0**edges if log else edges


def parse_fix(items: list[str] | None) -> dict[str, float]:
    """--fix NAME=VALUE items -> {name: value}; raises ValueError with a one-line reason."""
    fixed: dict[str, float] = {}
    for item in items or []:
        name, sep, text = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ValueError(f"--fix {item}: expected NAME=VALUE, e.g. R1=0.5")
        try:
            value = float(text)
        except ValueError:
            raise ValueError(f"--fix {item}: '{text}' is not a number") from None
        if name in fixed:
            raise ValueError(f"--fix {name} is given twice")
        fixed[name] = value
    return fixed


def save_figure(fig, path: str, dpi: int) -> None:
    """Writes a matplotlib figure and closes it; VibromapFileError names the path on failure."""
    import matplotlib.pyplot as plt  # only the plotting scripts need matplotlib

    try:
        fig.savefig(path, dpi=dpi)
    except OSError as exc:
        raise VibromapFileError(f"{path}: cannot write ({exc.strerror or exc})") from exc
    finally:
        plt.close(fig)


@dataclasses.dataclass
class BasinAttractor:
    """One attractor of a basins file (include/vibromap/io/basins_file.hpp)."""

    regime: str  # "(n,k)" or a regime kind
    n: int
    k: int
    k_con: float
    T_con: float  # s
    F_max: float  # N
    stable: int  # 1, 0, -1 unknown
    soft: bool
    pixels: int
    fraction: float  # of the pixels followed (overlap excluded)
    strobe: np.ndarray  # (n, 4): stroboscopic states x1, x2, v1, v2


@dataclasses.dataclass
class Basins:
    """A plane of initial states labelled by attractor (`vibromap basins`)."""

    path: str
    x_name: str  # first plane variable: x1, x2, v1 or v2
    y_name: str
    x: np.ndarray  # its values (m or m/s)
    y: np.ndarray
    x_units: str
    y_units: str
    label: np.ndarray  # (len(y), len(x)) int: attractor index, -1 unresolved, -2 unlisted, -3 overlap, -4 not computed
    fixed: str  # "x2=0.05 v2=0": the variables outside the plane
    fixed_state: np.ndarray  # (4,) the state before the plane variables are set
    complete: bool
    scene: str
    attractors: list


BASINS_UNRESOLVED, BASINS_UNLISTED, BASINS_OVERLAP, BASINS_NOT_COMPUTED = -1, -2, -3, -4


def read_basins(path: str) -> Basins:
    """Reads a basins file, or raises VibromapFileError with a one-line reason."""
    with open_h5(path) as f:
        plane = _text(f.attrs.get("plane", ""))
        if "," not in plane or "label" not in f:
            raise VibromapFileError(f"{path}: not a basins file of vibromap basins (no plane or label)")
        x_name, y_name = plane.split(",", 1)
        if x_name not in f or y_name not in f:
            raise VibromapFileError(f"{path}: the plane's coordinates '{plane}' are missing")
        label = np.asarray(f["label"][()], dtype=int)
        x, y = np.asarray(f[x_name][()]), np.asarray(f[y_name][()])
        if label.shape != (y.size, x.size):
            raise VibromapFileError(f"{path}: 'label' is {label.shape}, the plane {y.size} x {x.size}")
        count = _scalar(f.attrs.get("attractors", 0), path, "attractors", int)
        attractors = []
        kinds = _flag_meanings(f["regime"], None, "", path) if count else {}
        for a in range(count):
            code = int(f["regime"][a])
            n, k = int(f["n"][a]), int(f["k"][a])
            points = int(f["strobe_points"][a])
            attractors.append(BasinAttractor(
                regime=f"({n},{k})" if code == REGIME_PERIODIC else kinds.get(code, str(code)).replace("_", "-"),
                n=n, k=k, k_con=float(f["k_con"][a]), T_con=float(f["T_con"][a]), F_max=float(f["F_max"][a]),
                stable=int(f["stable"][a]), soft=bool(f["soft"][a]), pixels=int(f["pixels"][a]),
                fraction=float(f["fraction"][a]), strobe=np.asarray(f["strobe"][a, :points, :])))
        return Basins(path=os.fspath(path), x_name=x_name, y_name=y_name, x=x, y=y,
                      x_units=_text(f[x_name].attrs.get("units", "")), y_units=_text(f[y_name].attrs.get("units", "")),
                      label=label, fixed=_text(f.attrs.get("fixed", "")),
                      fixed_state=np.asarray(f.attrs.get("fixed_state", np.full(4, np.nan)), dtype=float),
                      complete=bool(_scalar(f.attrs.get("complete", 0), path, "complete", int)),
                      scene=_text(f.attrs.get("scene", "")), attractors=attractors)
