"""Reading the files of one parameter point: a kept trajectory (`vibromap run --trajectory`) and
a basins plane (`vibromap basins`). Part of the readers that vibromap._io gathers (import them
from there).

Trajectory file (src/io/trajectory_file.cpp, include/vibromap/io/trajectory_file.hpp):
  datasets  t (s), x1, x2 (m), v1, v2 (m/s), Fc, F (N): 1-D float64 of equal length,
            each with a `units` attribute; t is the time since the start of the kept window
  root attributes  T (s), regime ("(n,k)" or a kind such as "chatter"), n, k,
            T_con (s), k_con (-), scene (the scene's TOML text), vibromap_version, version
            (FORMAT_VERSIONS["trajectory file"]), attribute_checksum

Basins file (include/vibromap/io/basins_file.hpp; version FORMAT_VERSIONS["basins file"]): see
read_basins and Basins.
"""

from __future__ import annotations

import dataclasses
import os

import h5py
import numpy as np

from .h5io import VibromapFileError, _flag_meanings, _scalar, _text, open_h5
from .regimes import REGIME_PERIODIC

TRAJECTORY_COLUMNS = ("t", "x1", "x2", "v1", "v2", "Fc", "F")
TRAJECTORY_ATTRIBUTES = ("T", "regime", "n", "k", "T_con", "k_con", "scene", "vibromap_version")


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


def read_trajectory(path: str) -> Trajectory:
    """Reads a trajectory file written by vibromap (see the module docstring for the layout)."""
    path = os.fspath(path)
    with open_h5(path, "trajectory file") as f:
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
class BasinEntropy:
    """The basin entropy of a basins file's labels (root attributes; basin_entropy.hpp, docs/model.md)."""

    box: int  # side of the boxes, pixels
    boxes: int
    boundary_boxes: int  # boxes holding more than one outcome
    S_b: float  # basin entropy, nats
    S_bb: float  # boundary basin entropy, nats
    log2_test: str  # "fractal" (S_bb > ln 2), "not_shown" (S_bb <= ln 2: proves nothing), "no_boundary"
    uncertain: np.ndarray  # f(eps) at eps = 1, 2, 4, ... pixels
    alpha: float  # uncertainty exponent, NaN when not fitted
    dimension: float  # 2 - alpha
    fit_eps: tuple  # (lo, hi) pixels of the fitted scales; (0, 0) when not fitted
    fit_rms: float  # RMS residual of the fit in ln f
    note: str  # why alpha was not fitted


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
    entropy: BasinEntropy | None = None  # None in a file written before vibromap computed it


BASINS_UNRESOLVED, BASINS_UNLISTED, BASINS_OVERLAP, BASINS_NOT_COMPUTED = -1, -2, -3, -4
# Root attributes every basins file has.
BASINS_ATTRIBUTES = ("scene", "plane", "fixed", "fixed_state", "complete", "attractors")


def _read_basin_entropy(f, path: str) -> BasinEntropy | None:
    """The root attributes of the basin entropy, None when the file has none (an older file)."""
    if "basin_entropy" not in f.attrs:
        return None
    a = f.attrs

    def number(name, kind=float):
        return _scalar(a[name], path, name, kind)

    return BasinEntropy(
        box=number("entropy_box", int), boxes=number("entropy_boxes", int),
        boundary_boxes=number("entropy_boundary_boxes", int), S_b=number("basin_entropy"),
        S_bb=number("boundary_basin_entropy"), log2_test=_text(a["log2_test"]),
        uncertain=np.asarray(a.get("uncertainty_fraction", np.zeros(0)), dtype=float).reshape(-1),
        alpha=number("uncertainty_exponent"), dimension=number("boundary_dimension"),
        fit_eps=(number("uncertainty_fit_eps_lo", int), number("uncertainty_fit_eps_hi", int)),
        fit_rms=number("uncertainty_fit_rms"), note=_text(a["uncertainty_note"]))


def read_basins(path: str) -> Basins:
    """Reads a basins file, or raises VibromapFileError with a one-line reason."""
    with open_h5(path, "basins file") as f:
        for name in BASINS_ATTRIBUTES:
            if name not in f.attrs:
                raise VibromapFileError(f"{path}: not a basins file of vibromap basins (no root attribute '{name}')")
        plane = _text(f.attrs["plane"])
        if "," not in plane or "label" not in f:
            raise VibromapFileError(f"{path}: not a basins file of vibromap basins (no plane or label)")
        x_name, y_name = plane.split(",", 1)
        if x_name not in f or y_name not in f:
            raise VibromapFileError(f"{path}: the plane's coordinates '{plane}' are missing")
        label = np.asarray(f["label"][()], dtype=int)
        x, y = np.asarray(f[x_name][()]), np.asarray(f[y_name][()])
        if label.shape != (y.size, x.size):
            raise VibromapFileError(f"{path}: 'label' is {label.shape}, the plane {y.size} x {x.size}")
        count = _scalar(f.attrs["attractors"], path, "attractors", int)
        attractors = []
        kinds = _flag_meanings(f["regime"], path) if count else {}
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
                      x_units=_text(f[x_name].attrs["units"]), y_units=_text(f[y_name].attrs["units"]),
                      label=label, fixed=_text(f.attrs["fixed"]),
                      fixed_state=np.asarray(f.attrs["fixed_state"], dtype=float),
                      complete=bool(_scalar(f.attrs["complete"], path, "complete", int)),
                      scene=_text(f.attrs["scene"]), attractors=attractors,
                      entropy=_read_basin_entropy(f, path))
