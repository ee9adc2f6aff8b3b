"""vibromap in Python: one parameter point of the vibro-impact model, solved by the C++ core.

    >>> import vibromap
    >>> scene = vibromap.Scene.from_toml("jobs/paper/table2.toml")
    >>> r = vibromap.run(scene)
    >>> r.k_con, r.regime, r.soft
    (8.962737561620393, '(1,1)', True)
    >>> vibromap.run(scene.with_(**{"contact.E2": 2e6})).k_con
    >>> vibromap.census(scene, k=16).fractions()
    {'(3,3)': 0.625, '(1,1)': 0.375}

The numbers are those of ``vibromap run SCENE [--census] --format json``, bit for bit: the same scene
reader, solver and JSON writer. Branches and curves (``branch``, ``curve``), the optimisation
(``optimise``) and maps (``sweep``, census maps too) are run by the vibromap program itself, as
its commands run them (maps on MPI ranks under mpirun), and return its numbers and files. Keys, units, ranges and defaults: ``vibromap.Scene.keys()``
(the command line's ``vibromap keys``). docs/python.md explains the package.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Dict, Optional

if TYPE_CHECKING:
    import xarray

from ._native import SceneError, _core  # the compiled core, or a stand-in saying it is not built

SceneError.__module__ = __name__  # tracebacks name vibromap.SceneError, where users import it
from ._result import Census, Result
from ._scene import KeyInfo, Scene, Value
from ._studies import Branch, Curves, Optimisation, branch, curve, optimise, sweep

__all__ = ["Scene", "KeyInfo", "Result", "Census", "SceneError", "run", "census", "trajectory",
           "Branch", "Curves", "Optimisation", "branch", "curve", "optimise", "sweep"]
__version__ = "0.1.0"


def __getattr__(name: str):
    """vibromap.files and vibromap.plot, imported when first used (they need h5py, matplotlib)."""
    if name in ("files", "plot"):
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def run(scene: Scene, **keys: Value) -> Result:
    """Solves the point of ``scene`` (with ``keys`` set) as ``vibromap run SCENE --format json``.

    Returns a :class:`Result` with every quantity of that JSON, bit for bit: regime, k_con,
    T_con, F_max, soft, stability, the impacts, the Floquet multipliers, ... (``r.to_dict()``).

    Raises :class:`SceneError` (a ValueError) with the command line's one-line message for a
    bad key or value, or when the solver refuses the point. The GIL is released while the
    point is solved, so threads (``concurrent.futures.ThreadPoolExecutor``) solve points at
    once; Ctrl-C in the main thread stops the solve within milliseconds (KeyboardInterrupt).
    No trajectory is kept (``run`` without ``--trajectory``).
    """
    return Result.from_json(_core.run_json(_scene_of("run", scene, keys)._scene))


def census(scene: Scene, k: Optional[int] = None, *, labels: bool = False, shock: bool = False,
           **keys: Value) -> Census:
    """Every attractor of the point of ``scene``, as ``vibromap run SCENE --census --format json``.

    ``k`` initial states (census.initial_conditions; the scene's [census] or its defaults
    otherwise) are followed to their attractors in this process, one after the other; returns a
    :class:`Census` with each attractor's regime, k_con, soft flag and basin fraction, bit for
    bit the command's numbers. ``labels`` keeps each initial state and its attractor
    (``--labels``), ``shock`` finds each attractor's minimal critical shock (``--shock``).
    ``keys`` set more keys, [census] ones included (``**{"census.seed": 3}``).

    Raises :class:`SceneError` as :func:`run` does; releases the GIL and stops on Ctrl-C as it.
    """
    if k is not None:
        keys = {"census.initial_conditions": k, **keys}
    return Census.from_json(_core.census_json(_scene_of("census", scene, keys)._scene, labels, shock))


def trajectory(scene: Scene, periods: Optional[int] = None, *, samples: Optional[int] = None,
               **keys: Value) -> "xarray.Dataset":
    """The steady motion of the point of ``scene`` as an xarray Dataset, as ``run --trajectory``.

    ``periods`` forcing periods (analysis.trajectory_periods; the scene's, or 2 when it gives
    0) of ``samples`` samples each (analysis.trajectory_samples) are kept after the steady
    state: the Dataset has the coordinate ``t`` (s, since the window's start) and the
    variables ``x1``, ``x2`` (m), ``v1``, ``v2`` (m/s), ``Fc`` and ``F`` (N), each with its
    ``units`` and ``description``, the values of the file ``vibromap run SCENE --trajectory
    FILE`` writes, bit for bit; its attributes are the file's (T, regime, n, k, T_con, k_con,
    scene) and ``result``, the point's :class:`Result`. Needs xarray.
    """
    import xarray

    if periods is not None:
        keys = {"analysis.trajectory_periods": periods, **keys}
    if samples is not None:
        keys = {"analysis.trajectory_samples": samples, **keys}
    text, scene_text, columns = _core.trajectory(_scene_of("trajectory", scene, keys)._scene)
    result = Result.from_json(text)
    (t_name, t_units, t_description, t), *others = columns
    coords = {t_name: (t_name, t, {"units": t_units, "description": t_description})}
    data = {name: (t_name, values, {"units": units, "description": description})
            for name, units, description, values in others}
    attrs = {"T": result.T, "regime": result.regime, "n": result.n, "k": result.k, "T_con": result.T_con,
             "k_con": result.k_con, "scene": scene_text, "result": result}
    return xarray.Dataset(data, coords=coords, attrs=attrs)


def _scene_of(caller: str, scene: Scene, keys: Dict[str, Value]) -> Scene:
    if not isinstance(scene, Scene):
        raise TypeError(f"{caller}() takes a vibromap.Scene, not {type(scene).__name__} (Scene.from_toml(path))")
    return scene.with_(**keys) if keys else scene
