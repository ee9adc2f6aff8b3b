"""The pictures of vibromap's files: one function per picture, each returning a matplotlib Figure.

    >>> import vibromap.files, vibromap.plot
    >>> fig = vibromap.plot.regime_map("map.h5", x="E1", y="E2")
    >>> fig.savefig("regimes.png")          # or show it in a notebook
    >>> fig = vibromap.plot.trajectory(vibromap.files.open("traj.h5"), periods=1)

Each takes a path or the Dataset vibromap.files.open gave for it (a trajectory also the Dataset
of vibromap.trajectory(scene)). A file is checked as vibromap.files.open checks it (in a forked
child: version, checksum, every dataset read) before its picture reads it, so a damaged file
raises vibromap.files.DamagedFileError (a ValueError), never a crash. No figure is shown or
written and pyplot's list of figures is left alone: the Figure is the caller's (any backend,
Agg included). The notes the scripts print (axes snapped to grid values, soft cells) are the
Figure's attribute ``vibromap_notes``. The scripts of vibromap-post draw the same figures.
"""

from __future__ import annotations

import os

__all__ = ["regime_map", "kcon_map", "soft_map", "census_map", "basins", "branch", "orbit_diagram",
           "optimise", "restitution", "trajectory", "work_precision"]


def _path(source, kind: str | None = None, *, hdf5: bool = True) -> str:
    """The file behind source (a path, or a Dataset of vibromap.files.open), checked as a file of
    kind (the one line of open_h5 for a file of another kind or version)."""
    from .. import files

    if hasattr(source, "encoding") and hasattr(source, "data_vars"):
        path = source.encoding.get("source")
        if not path:
            raise TypeError("this Dataset has no file behind it: give the path, or the Dataset of vibromap.files.open")
    else:
        path = os.fspath(source)
    if hdf5:
        files.checked(path, kind)
    return path


def _map_figure(module, source, x, y, fix, curves, solved, prepare=None):
    """A map picture: the map read, prepare(sweep) -> (extra args, notes), a slice, the figure."""
    from .._io import read_map
    from . import _regime_map as maps

    sweep = read_map(_path(source, "regime map"))
    extra, notes = prepare(sweep) if prepare else ((), [])
    sl = maps.choose_slice(sweep, x, y, dict(fix or {}))
    curve_files = maps.read_curve_files([_path(c, "curve file") for c in curves])
    fig = module.plot(sweep, sl, *extra, curve_files)
    if solved:
        maps.mark_solved(fig, sweep, sl)
    fig.vibromap_notes = maps.snapped_notes(sl) + notes
    return fig


def regime_map(source, x: str | None = None, y: str | None = None, fix: dict | None = None, curves=(),
               solved: bool = False):
    """The regime of each cell of a 2-D slice of a map (plot_regime_map): x, y the axes shown,
    fix {axis: value} the grid values of the others, curves the curve files drawn over it,
    solved marks an adaptive map's solved points."""
    from . import _regime_map

    return _map_figure(_regime_map, source, x, y, fix, curves, solved)


def kcon_map(source, x: str | None = None, y: str | None = None, fix: dict | None = None, curves=(),
             solved: bool = False, threshold: float | None = None):
    """k_con of each cell, the soft region outlined (plot_kcon_map); threshold: soft_kcon."""
    from .._io import add_soft_cells
    from . import _kcon_map, _regime_map as maps

    def prepare(sweep):
        _kcon_map.require_kcon(sweep)
        info = add_soft_cells(sweep, threshold)
        return (info,), maps.soft_notes(info)

    return _map_figure(_kcon_map, source, x, y, fix, curves, solved, prepare)


def soft_map(source, x: str | None = None, y: str | None = None, fix: dict | None = None, curves=(),
             solved: bool = False):
    """Where the motion is soft, Hertz-invalid cells hatched (plot_soft_map)."""
    from .._io import add_soft_cells
    from . import _regime_map as maps, _soft_map

    def prepare(sweep):
        info = add_soft_cells(sweep)
        return (info,), maps.soft_notes(info)

    return _map_figure(_soft_map, source, x, y, fix, curves, solved, prepare)


def census_map(source, show: str = "attractors", x: str | None = None, y: str | None = None,
               fix: dict | None = None, curves=(), family: int | None = None, at: dict | None = None,
               solved: bool = False):
    """A census map (plot_census_map --show SHOW): attractors, soft, families, family, shock,
    or cell (the census of the cell nearest ``at`` {axis: value})."""
    from . import _census_map

    return _census_map.figure(_path(source, "regime map"), show, x, y, dict(fix or {}),
                              [_path(c, "curve file") for c in curves], family,
                              dict(at or {}), solved)


def basins(source):
    """The attractor of each initial state of a basins plane (plot_basins)."""
    from .._io import read_basins
    from . import _basins

    return _basins.plot(read_basins(_path(source, "basins file")))


def branch(source, diagram=None):
    """A branch of vibromap continue and its bifurcations, an orbit diagram under it (plot_branch);
    source may also be the saved JSON of continue --format json."""
    from . import _branch

    path = _path(source, hdf5=False)
    if _is_hdf5(path):
        _path(path, "branch file")
    return _branch.plot(_branch.read_branch(path), None if diagram is None else _path(diagram, "orbit-diagram file"))


def orbit_diagram(source, var: str = "x1"):
    """The states kept at each step of an orbit diagram, swept up and down (plot_orbit_diagram)."""
    from . import _orbit_diagram

    return _orbit_diagram.plot(_path(source, "orbit-diagram file"), var)


def optimise(source, show: str = "convergence", x: str | None = None, y: str | None = None,
             fix: dict | None = None):
    """An optimisation (plot_optimise): show "convergence" (every start's running best), "map"
    (the starts and best points over the regime map it was seeded from, FILE_map.h5 beside it)
    or "best" (the best point's trajectory, FILE_trajectory.h5 beside it)."""
    from . import _optimise

    return _optimise.figure(_path(source, "optimisation file"), show, x, y, dict(fix or {}))


def restitution(source):
    """The effective restitution of each contact law against its e (plot_restitution), from the
    JSON of vibromap restitution --format json."""
    from . import _restitution

    return _restitution.make_figure(_restitution.read_rows(_path(source, hdf5=False)))


def trajectory(source, periods: float | None = None):
    """Displacements and forces of a kept trajectory over its first ``periods`` forcing periods
    (plot_trajectory); source may be the Dataset of vibromap.trajectory(scene)."""
    from . import _trajectory

    traj = _trajectory.from_dataset(source) if _no_file(source) else _trajectory.read(_path(source, "trajectory file"))
    return _trajectory.plot(traj, _trajectory.select_periods(traj, periods))


def work_precision(source, quantity: str = "k_con"):
    """Relative error against solve time of each method of vibromap accuracy --csv
    (plot_work_precision)."""
    from . import _work_precision

    return _work_precision.plot(_work_precision.read_study(_path(source, hdf5=False)), quantity)


def _no_file(source) -> bool:
    return hasattr(source, "data_vars") and not source.encoding.get("source")


def _is_hdf5(path: str) -> bool:
    """Whether path starts with HDF5's signature; a file that cannot be opened is left to the
    reader, which names it in its one line."""
    try:
        with open(path, "rb") as f:
            return f.read(8) == b"\x89HDF\r\n\x1a\n"
    except OSError:
        return False
