"""Slices of a map for plotting: slice2d() takes a 2-D slice (or a 1-D strip) with the other axes
held at a grid value; cell_edges() and cell_boundary() draw its cells; parse_fix() reads the
scripts' --fix NAME=VALUE. Part of the readers that vibromap._io gathers (import them from there).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .map import MapAxis, SweepMap, axis_name
from .regimes import regime_labels


class MapSliceError(ValueError):
    """A slice of a map cannot be taken: unknown axis name, an axis used twice, a bad value."""


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
