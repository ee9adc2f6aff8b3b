"""Studies the vibromap program runs: a branch and its curves (``vibromap continue``), the
optimisation (``vibromap optimise``) and maps (``vibromap sweep``, census maps included).

Each is run by the program itself, as the command line runs it, so that its numbers and files
are the command's, bit for bit, and a map runs on the one farm (MPI ranks under ``mpirun``,
checkpoints, resume). The program is found next to the package: ``build/vibromap`` for the
build tree's package (``PYTHONPATH=build/python``), ``PREFIX/bin/vibromap`` for one installed
under ``PREFIX``, else ``vibromap`` on ``PATH``; the environment variable ``VIBROMAP_EXE``
names another.

A scene read from a file (and changed by ``with_``) is given to the program as that file and
its ``--set`` overrides, the command line a user would type; another scene as its TOML text in a
temporary file, whose name the messages give as the scene's path.

The program runs in a session of its own, so that a terminal's Ctrl-C reaches Python only; the
call then sends the program SIGUSR1 (its stop signal, which mpirun forwards to the ranks where
it would turn SIGINT into a kill), waits for its final checkpoint and raises KeyboardInterrupt.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union

from ._result import _Answer
from ._scene import Scene, Value

if TYPE_CHECKING:
    import xarray

PathLike = Union[str, "os.PathLike[str]"]

from ._program import _SceneArgs, _Progress, _CENSUS_K, _execute, _answer

def _open(path: PathLike, group: Optional[str] = None) -> "xarray.Dataset":
    """A file vibromap wrote, as vibromap.files.open gives it: read into memory (the file is
    closed), its codes named beside them (``soft_name``, ``regime_name``, ...), checked whole
    first (a damaged file raises vibromap.files.DamagedFileError, a ValueError)."""
    from . import files

    return files.open(path, group)


def _output(output: Optional[PathLike], scene: Scene, suffix: str) -> str:
    """The output file: as given, else the command's default (the scene file's stem + suffix)."""
    if output is not None:
        return os.fspath(output)
    if not scene.path.endswith(".toml"):
        raise ValueError(f"output: needed for a scene not read from a file ({scene.path})")
    return Path(scene.path).stem + suffix


def _resume_flags(output: str, resume: Optional[bool], overwrite: bool) -> List[str]:
    if resume and overwrite:
        raise ValueError("resume and overwrite exclude each other")
    if overwrite:
        return ["--overwrite"]
    if resume or (resume is None and os.path.exists(output)):
        return ["--resume"]
    return []


def _number(name: str, value: float) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"{name} must be a number, not {type(value).__name__}")
    return repr(float(value))


# ---- results --------------------------------------------------------------------------------

class _Study(_Answer):
    """A study's JSON quantities as attributes, with the files it wrote as xarray Datasets."""

    __slots__ = ("_files",)

    def __init__(self, data: Dict[str, Any], files: Dict[str, Any]) -> None:
        super().__init__(data)
        self._files = files

    def __getstate__(self) -> Dict[str, Any]:  # type: ignore[override]
        return {"data": self._data, "files": self._files}

    def __setstate__(self, state: Dict[str, Any]) -> None:  # type: ignore[override]
        self._data, self._files = state["data"], state["files"]

    def __eq__(self, other: object) -> bool:
        return type(other) is type(self) and self._data == other._data


class Branch(_Study):
    """A periodic orbit followed in one key: ``vibromap continue SCENE --param KEY --from A --to B``.

    The quantities of its ``--format json`` output, bit for bit: ``key``, ``n`` (period, forcing
    periods), ``stop`` (why branch 0 ended), ``points`` (each a dict: param, stable,
    multipliers as [re, im], T_con, k_con, F_max, impacts, x1_max, x2_max, clearance_min,
    regime, y, strobe_x1), ``bifurcations`` (each with its type: fold, period-doubling,
    neimark-sacker, grazing; param; the orbit there) and ``branches`` (those switched onto at
    period doublings, each with its points and bifurcations). ``dataset`` is the branch file
    ``continue -o`` writes (docs/file-formats.md, "Branch file") as an xarray Dataset: every
    branch's points along the dimension ``point``, ``bifurcation_*`` along ``bifurcation``.
    docs/guide-continuation.md explains them.
    """

    __slots__ = ()

    @property
    def dataset(self) -> "xarray.Dataset":
        """The branch file as an xarray Dataset."""
        return self._files["branch"]

    @property
    def params(self) -> List[float]:
        """The key's value at each point of branch 0."""
        return [p["param"] for p in self._data["points"]]

    def __repr__(self) -> str:
        d = self._data
        found = ", ".join(f"{b['type']} at {b['param']:.6g}" for b in d.get("bifurcations", []))
        return (f"Branch(key={d.get('key')!r}, n={d.get('n')}, points={len(d.get('points', []))}, "
                f"branches={1 + len(d.get('branches', []))}, bifurcations=[{found}], stop={d.get('stop')!r})")


class Curves(Branch):
    """Curves of codimension-one points in two keys: ``vibromap continue ... --curve KIND
    --param2 KEY2 --from2 C --to2 D``.

    The branch's quantities (as :class:`Branch`, but ``dataset``: the curve file holds the
    curves only), then ``curves`` (each a dict: kind, n, stop, start, codim2, points with
    param, param2, T_con, k_con, z_ratio, F_max, impacts, stable, multipliers, residual, ...)
    and ``skipped`` (the starts not followed, and why), bit for bit the command's JSON.
    ``datasets`` are the curve file's groups (``curve_0``, ...) as xarray Datasets, with the
    file's root attributes (param, param2, their units) added to each.
    """

    __slots__ = ()

    @property
    def dataset(self) -> "xarray.Dataset":
        raise AttributeError("Curves has no branch file (continue --curve writes the curve file): see datasets, "
                             "or vibromap.branch() for the branch's")

    @property
    def datasets(self) -> List["xarray.Dataset"]:
        """Each curve of the curve file as an xarray Dataset."""
        return self._files["curves"]

    def __repr__(self) -> str:
        d = self._data
        kinds = ", ".join(f"{c['kind']} ({len(c['points'])} points)" for c in d.get("curves", []))
        return f"Curves(key={d.get('key')!r}, curves=[{kinds}], skipped={len(d.get('skipped', []))})"


class Optimisation(_Study):
    """A multistart optimisation: ``vibromap optimise SCENE --format json``.

    Every quantity of that JSON, bit for bit (``best``: the best distinct points re-solved from
    scratch, best first, each with its parameters, objective, regime, k_con, T_con, F_max, ...;
    docs/guide-optimise.md explains them). ``output`` names the result file (every evaluation
    of every start) and ``dataset`` its root (the box, the seeds) as an xarray Dataset,
    ``group("starts/000")`` one of its groups (each start's evaluations, each best point's
    re-solves: docs/file-formats.md); ``trajectory`` the best point's steady motion
    (FILE_trajectory.h5) when the run wrote it.
    """

    __slots__ = ()

    @property
    def output(self) -> str:
        return self._files["output"]

    @property
    def dataset(self) -> "xarray.Dataset":
        return self._files["dataset"]

    @property
    def trajectory(self) -> Optional["xarray.Dataset"]:
        return self._files.get("trajectory")

    def group(self, name: str) -> "xarray.Dataset":
        """The result file's group ``name`` ("starts/000", "best/00/shooting") as an xarray Dataset."""
        return _open(self.output, name)

    def __repr__(self) -> str:
        best = self._data.get("best") or []
        return f"Optimisation(best={len(best)} points, output={self._files.get('output')!r})"


# ---- the studies ------------------------------------------------------------------------------

def _continue_args(param: str, from_: float, to: float, ds_max: Optional[float], max_points: Optional[int],
                   pd_depth: Optional[int]) -> List[str]:
    args = ["--param", param, "--from", _number("from_", from_), "--to", _number("to", to)]
    if ds_max is not None:
        args += ["--ds-max", _number("ds_max", ds_max)]
    if max_points is not None:
        args += ["--max-points", str(int(max_points))]
    if pd_depth is not None:
        args += ["--pd-depth", str(int(pd_depth))]
    return args


def _continue(scene: Scene, keys: Dict[str, Value], study: List[str], output: Optional[PathLike],
              overwrite: bool) -> Tuple[Dict[str, Any], str, Optional[str]]:
    """Runs ``vibromap continue`` and returns its JSON, the file it wrote and the temporary
    folder that holds it when no output was asked (the caller removes it)."""
    given = _SceneArgs(scene, keys)
    folder = None
    try:
        if output is None:
            folder = tempfile.mkdtemp(prefix="vibromap-continue-")
            path = os.path.join(folder, "continue.h5")
        else:
            path = os.fspath(output)
        args = ["continue", *given.args, *study, "-o", path, "--format", "json"] + (["--overwrite"] if overwrite else [])
        data = json.loads(_answer(_execute(args, 1, _Progress(False)), given))
        return data, path, folder
    except BaseException:
        if folder:
            shutil.rmtree(folder, ignore_errors=True)
        raise
    finally:
        given.close()


def branch(scene: Scene, param: str, from_: float, to: float, *, ds_max: Optional[float] = None,
           max_points: Optional[int] = None, pd_depth: Optional[int] = None, output: Optional[PathLike] = None,
           overwrite: bool = False, **keys: Value) -> Branch:
    """The periodic orbit of ``scene`` followed in the key ``param`` from ``from_`` to ``to``,
    as ``vibromap continue SCENE --param PARAM --from A --to B --format json -o FILE``.

    The orbit the point settles into from rest at ``param = from_`` is followed by
    pseudo-arclength continuation through folds to ``to``; its Floquet multipliers, stability,
    regime, k_con, T_con and F_max are measured at every point, and its bifurcations (fold,
    period-doubling, Neimark-Sacker, grazing) located. At each period doubling the doubled
    branch is followed too, to ``pd_depth`` generations (the command's --pd-depth, 1). ``ds_max``
    is the largest step (scaled arclength, --ds-max, 0.05), ``max_points`` the points per branch
    at most (--max-points, 5000). ``keys`` set more keys of the scene first.

    Returns a :class:`Branch`: the command's JSON quantities bit for bit (``points``,
    ``bifurcations``, ``branches``, ...) and ``dataset``, the branch file as an xarray Dataset.
    The file is written to ``output`` when given (``overwrite`` replaces one), else to a
    temporary file that is removed once read.

    The command runs as a program of its own (found as the module explains). Raises
    :class:`SceneError` with the command line's one-line message for bad input (a key that is
    not a model parameter, ``from_ == to``, no periodic orbit at the start, an existing output);
    Ctrl-C stops it within a second (KeyboardInterrupt; a given ``output`` then holds the
    branch so far, a whole file, as the command's stop leaves it).
    """
    data, path, folder = _continue(scene, keys, _continue_args(param, from_, to, ds_max, max_points, pd_depth),
                                   output, overwrite)
    try:
        return Branch(data, {"branch": _open(path)})
    finally:
        if folder:
            shutil.rmtree(folder, ignore_errors=True)


def curve(scene: Scene, param: str, from_: float, to: float, kind: Union[str, Sequence[str]], param2: str,
          from2: float, to2: float, *, ds_max: Optional[float] = None, max_points: Optional[int] = None,
          pd_depth: Optional[int] = None, output: Optional[PathLike] = None, overwrite: bool = False,
          **keys: Value) -> Curves:
    """Curves of bifurcation or level points in two keys, as ``vibromap continue SCENE --param
    PARAM --from A --to B --curve KIND --param2 PARAM2 --from2 C --to2 D --format json -o FILE``.

    The branch in ``param`` over [from_, to] at the scene's ``param2`` is followed as
    :func:`branch` follows it; then every point of each ``kind`` on it ("fold",
    "period-doubling", "neimark-sacker", "grazing", or "level:NAME=VALUE" with NAME one of
    k_con, T_con, F_max, z_ratio; a str or a list of them) is followed as a curve in
    (param, param2) both ways while ``param2`` stays in [from2, to2] and ``param`` in
    [from_, to]; codimension-two points met on a curve are located.

    Returns :class:`Curves`: the command's JSON bit for bit (the branch's quantities, ``curves``
    and ``skipped``) and ``datasets``, each curve of the curve file as an xarray Dataset. The
    file goes to ``output`` when given, else to a temporary file removed once read. Errors and
    Ctrl-C as :func:`branch`.
    """
    kinds = [kind] if isinstance(kind, str) else list(kind)
    study = _continue_args(param, from_, to, ds_max, max_points, pd_depth)
    for k in kinds:
        study += ["--curve", k]
    study += ["--param2", param2, "--from2", _number("from2", from2), "--to2", _number("to2", to2)]
    data, path, folder = _continue(scene, keys, study, output, overwrite)
    try:
        import h5py

        with h5py.File(path, "r") as f:
            root = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
            groups = sorted((g for g in f if isinstance(f[g], h5py.Group)), key=lambda g: int(g.rsplit("_", 1)[-1]))
        shared = {k: root[k] for k in ("param", "param2", "param_unit", "param2_unit") if k in root}
        datasets = []
        for g in groups:
            ds = _open(path, g)
            ds.attrs.update(shared)
            datasets.append(ds)
        return Curves(data, {"curves": datasets})
    finally:
        if folder:
            shutil.rmtree(folder, ignore_errors=True)


def optimise(scene: Scene, *, ranks: int = 1, output: Optional[PathLike] = None, resume: Optional[bool] = None,
             overwrite: bool = False, progress: bool = True, **keys: Value) -> Optimisation:
    """The softest impact in the box of the scene's [optimise] section, as ``[mpirun -n RANKS]
    vibromap optimise SCENE -o OUTPUT --format json``.

    Seeds come from the [optimise] map, the scene's [sweep] (run first into OUTPUT_map.h5) or
    the scene's point; every seed is started with every local algorithm on ``ranks`` MPI ranks,
    and the best distinct points are re-solved from scratch (docs/guide-optimise.md). The
    answer does not depend on ``ranks``.

    ``output`` is the result file (default: the scene file's stem with ``_optimise.h5``).
    Finished starts are journaled: a run stopped by Ctrl-C (KeyboardInterrupt, within a second,
    after a final checkpoint) is finished by calling again with the same output (``resume``
    None resumes when its journal is there; True always, False never); ``overwrite`` replaces
    an existing result and recomputes the seeding sweep. ``progress`` shows the finished starts.

    Returns an :class:`Optimisation` (the command's JSON bit for bit, the result file as an
    xarray Dataset). Raises :class:`SceneError` with the command line's message for bad input.
    """
    given = _SceneArgs(scene, keys)
    try:
        path = _output(output, given.scene, "_optimise.h5")
        journal_resume = resume if resume is not None else os.path.exists(path + ".journal")
        flags = _resume_flags(path, journal_resume, overwrite)
        args = ["optimise", *given.args, "-o", path, "--format", "json", *flags]
        data = json.loads(_answer(_execute(args, ranks, _Progress(progress)), given))
    finally:
        given.close()
    stem = path[:-3] if path.endswith(".h5") else path
    files: Dict[str, Any] = {"output": path, "dataset": _open(path)}
    if os.path.exists(stem + "_trajectory.h5"):
        files["trajectory"] = _open(stem + "_trajectory.h5")
    return Optimisation(data, files)


def sweep(scene: Scene, ranks: int = 1, output: Optional[PathLike] = None, resume: Optional[bool] = None, *,
          overwrite: bool = False, census: Union[None, bool, int] = None, progress: bool = True,
          **keys: Value) -> "xarray.Dataset":
    """The map of the scene's [sweep] grid, as ``[mpirun -n RANKS] vibromap sweep SCENE -o OUTPUT``,
    returned as an xarray Dataset.

    Every cell is solved on the farm: ``ranks`` MPI ranks under mpirun (one: the program alone),
    the cells handed out as they finish, the map written by rank 0 and checkpointed every
    [sweep] checkpoint_interval seconds. ``output`` is the map file (default: the scene file's
    stem with ``.h5``). ``census`` makes it a census map (every attractor of every cell:
    True with the scene's [census] or K = 32 initial states, an int K for K; the command's
    ``--set census.initial_conditions=K``).

    A stopped map resumes: Ctrl-C raises KeyboardInterrupt within a second, after the program's
    final checkpoint (the file holds every cell done and opens), and calling again with the same
    scene and output finishes it (``resume`` None: resume when the output exists; True: always,
    as --resume; False: never, an existing output is then refused). ``overwrite`` replaces an
    existing map. ``progress`` shows the farm's progress: a line updated in place in a Jupyter
    notebook, the farm's own lines on stderr elsewhere.

    The Dataset has the map's axes as coordinates and its stored quantities as variables (the
    file's values bit for bit, docs/file-formats.md), its attributes the file's, and
    ``summary``, the run's JSON summary as text (cells computed and resumed, cells_per_s,
    regimes, ...). Raises :class:`SceneError` with the command line's one-line message for bad
    input (exit code 2: a scene without [sweep], an output of another run, ...).
    """
    if census is True and "\n[census]" not in scene.to_toml():
        census = _CENSUS_K
    if census is not None and not isinstance(census, bool):
        keys = {**keys, "census.initial_conditions": census}
    given = _SceneArgs(scene, keys)
    try:
        path = _output(output, given.scene, ".h5")
        shown = _Progress(progress)
        # A notebook's bar is updated every second; the farm's lines otherwise come at the scene's interval.
        interval = ["--set", "sweep.progress_interval=1"] if shown.notebook else [] if progress else ["-q"]
        args = ["sweep", *given.args, *interval, "-o", path, "--format", "json", *_resume_flags(path, resume, overwrite)]
        summary = _answer(_execute(args, ranks, shown), given)
    finally:
        given.close()
    ds = _open(path)
    ds.attrs["summary"] = summary
    return ds

