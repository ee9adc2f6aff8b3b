"""Plot what `vibromap optimise` found: how each start converged, where the starts went over
the regime map they were seeded from, and the best point's motion as the source paper shows it.

Three figures, named after the optimisation file OPT.h5 (or -o STEM; -o law.png is the stem law:
law_convergence.png, law_on_map.png, law_best.png):
  STEM_convergence.png  the objective (k_con, T_con or F_max) against the evaluation number,
                          one line per start in its own colour (line style: its algorithm),
                          labelled with its number, algorithm, seed point, best value and why
                          it stopped: every feasible evaluation as a dot, every
                          infeasible one (regime left, solve failed) as a grey cross where its
                          objective is defined, and the best feasible value so far as a line;
                          the overall best as a dashed level.
  STEM_on_map.png       the regime map of the seeding sweep (as plot_regime_map draws it), a
                          2-D slice through the best point (other axes held at the grid values
                          nearest to it, or --fix), with each start's path of improving feasible
                          points from its seed (circle) projected on the slice, and the best
                          points (stars, numbered as in the output). Needs the map: --map, or the
                          file the optimisation names in its seeds_from attribute.
  STEM_best.png         displacements and contact force of the best point's steady motion
                          (plot_trajectory's figure), from the trajectory file the optimisation
                          wrote beside OPT.h5; the title names the contact law and its
                          restitution (the best point's when restitution is free), and the
                          motion's Hertz validity
                          (z_max/R* against the limit: "Hertz-valid" or "Hertz-INVALID") from
                          the best point's re-solve from rest (best/00/integrate), when the
                          file holds its z_ratio or hertz_valid.
A figure whose input is missing (seeds from the scene's point: no map; no feasible point: no
trajectory) is skipped with a note.

The optimisation file's layout is include/vibromap/io/optimise_file.hpp's.

Exit status: 0 on success, 2 for a bad argument, an unreadable or invalid file, or one of another
format version (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via
vibromap-post).
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import sys

from .._guard import guarded_main

PROG = "plot_optimise"

import matplotlib
from . import _args, _figure
import numpy as np
from matplotlib.lines import Line2D

from .._io import (HERTZ_LIMIT_DEFAULT, MapSliceError, VibromapFileError, open_h5, read_map,
                   read_trajectory, regime_labels, save_figure)  # fmt: skip

from . import _regime_map as maps
from . import _trajectory as plot_trajectory

CONVERGENCE_FIGSIZE_IN = (9.0, 5.5)  # at the default 150 dpi: 1350 x 825 px
ALGORITHM_COLORS = {
    "bobyqa": "C0",
    "cobyla": "C1",
    "sbplx": "C2",
    "slsqp": "C4",
    "mma": "C5",
    "gradient_projection": "C3",
}
# On the map the paths of different algorithms from one seed overlap: each has its line style too.
ALGORITHM_LINESTYLES = {"bobyqa": "-", "cobyla": "-.", "sbplx": ":", "slsqp": "-.", "mma": ":",
                        "gradient_projection": "--"}  # fmt: skip
INFEASIBLE_COLOR = "0.55"
SEED_MARKER, BEST_MARKER = "o", "*"
LOG_RANGE = 10.0  # the objective axis is logarithmic when the values plotted span more than this factor


@dataclasses.dataclass
class Start:
    """One local optimisation: its evaluations in order (x in the file's variable order)."""

    index: int
    seed: int
    algorithm: str
    stop: str
    x: np.ndarray  # (E, V) parameters, SI
    objective: np.ndarray  # (E) the quantity (k_con, ...), NaN where undefined
    feasible: np.ndarray  # (E) bool
    labels: np.ndarray  # (E) regime labels "(1,1)", "chatter", ...
    best: int | None  # index of the best feasible evaluation
    law: str = ""  # the start's contact law when the law is a free variable ("" otherwise)


@dataclasses.dataclass
class Optimisation:
    """An optimisation file as read by read_optimise."""

    path: str
    variables: list[str]
    scales: list[str]
    bounds: np.ndarray  # (V, 2)
    quantity: str  # "k_con", "T_con" or "F_max"
    sense: str  # "minimise" or "maximise"
    regime: str  # the regime kept, "(1,1)" or "any"
    seeds_from: str  # the seeding map's path as given, or "scene"
    seeds: np.ndarray  # (S, V)
    starts: list[Start]
    best: list[dict]  # per best point: every parameter (E1, ..., omega2), objective, regime, k_con, ...
    trajectory: str  # the best point's trajectory file name ("" when none)
    hertz_limit: float = HERTZ_LIMIT_DEFAULT  # z_max/R* above which Hertz theory does not hold
    scene: str = ""  # the scene the optimisation ran (TOML text)

    def column(self, name: str) -> int | None:
        return self.variables.index(name) if name in self.variables else None


def _text(value) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return _text(value.reshape(()).item())
    return str(value)


def _read_start(group, path: str, variables: int) -> Start:
    for name in ("x", "objective", "feasible", "regime", "n", "k"):
        if name not in group:
            raise VibromapFileError(f"{path}: start {group.name} has no dataset '{name}'")
    for name in ("index", "seed", "algorithm", "stop", "best"):
        if name not in group.attrs:
            raise VibromapFileError(f"{path}: start {group.name} has no attribute '{name}'")
    x = np.asarray(group["x"][()], dtype=np.float64).reshape(-1, variables)
    best = int(group.attrs["best"])
    return Start(
        index=int(group.attrs["index"]),
        seed=int(group.attrs["seed"]),
        algorithm=_text(group.attrs["algorithm"]),
        stop=_text(group.attrs["stop"]),
        x=x,
        objective=np.asarray(group["objective"][()], dtype=np.float64),
        feasible=np.asarray(group["feasible"][()]) != 0,
        labels=regime_labels(group["regime"][()], group["n"][()], group["k"][()]),
        best=best if best >= 0 else None,
        law=_text(group.attrs.get("law", "")),  # only when the contact law is free
    )


def _read_best(group, path: str) -> dict:
    for name in ("law", "integrate"):
        if name not in group.attrs and name not in group:
            raise VibromapFileError(f"{path}: best point {group.name} has no '{name}'")
    for name in ("z_ratio", "hertz_valid"):
        if name not in group["integrate"].attrs:
            raise VibromapFileError(f"{path}: best point {group.name}/integrate has no attribute '{name}'")
    point = {name: float(value) for name, value in group.attrs.items() if np.asarray(value).dtype.kind in "iuf"}
    point["law"] = _text(group.attrs["law"])  # the best point's contact law
    # integrate/: the re-solve from rest; soft_check/: the soft-fraction re-check (min_soft_fraction > 0 only).
    for sub in ("integrate", "soft_check"):
        solve = group.get(sub)
        if solve is not None:
            for name, value in solve.attrs.items():
                point[f"{sub}_{name}"] = _text(value) if np.asarray(value).dtype.kind in "SUO" else value
    return point


def scene_table(scene: str, section: str) -> dict:
    """The [section] table of a scene's TOML text ({} when absent or unreadable)."""
    try:
        import tomllib  # Python >= 3.11

        table = tomllib.loads(scene).get(section, {})
        return table if isinstance(table, dict) else {}
    except (ImportError, ValueError, TypeError, AttributeError):
        return {}


def scene_hertz_limit(scene: str) -> float:
    """The Hertz limit the optimisation ran with: its scene's [analysis] hertz_limit, else the
    key's default (0.05)."""
    try:
        return float(scene_table(scene, "analysis").get("hertz_limit", HERTZ_LIMIT_DEFAULT))
    except (ValueError, TypeError):
        return HERTZ_LIMIT_DEFAULT


# Root attributes and datasets every optimisation file has (optimise_file.hpp).
OPTIMISE_ATTRIBUTES = ("scene", "variables", "scales", "quantity", "sense", "regime", "seeds_from", "trajectory")
OPTIMISE_ITEMS = ("bounds", "seeds", "starts", "best")


def read_optimise(path: str) -> Optimisation:
    """Reads an optimisation file written by vibromap optimise (optimise_file.hpp's layout)."""
    path = os.fspath(path)
    with open_h5(path, "optimisation file") as f:
        for name in OPTIMISE_ATTRIBUTES:
            if name not in f.attrs:
                raise VibromapFileError(f"{path}: not a vibromap optimisation file (no attribute '{name}')")
        for name in OPTIMISE_ITEMS:
            if name not in f:
                raise VibromapFileError(f"{path}: not a vibromap optimisation file (no '{name}')")
        variables = _text(f.attrs["variables"]).split()
        starts = [_read_start(f["starts"][name], path, len(variables)) for name in sorted(f["starts"])]
        scene = _text(f.attrs["scene"])
        return Optimisation(
            path=path,
            variables=variables,
            scales=_text(f.attrs["scales"]).split(),
            bounds=np.asarray(f["bounds"][()], dtype=np.float64).reshape(-1, 2),
            quantity=_text(f.attrs["quantity"]),
            sense=_text(f.attrs["sense"]),
            regime=_text(f.attrs["regime"]),
            seeds_from=_text(f.attrs["seeds_from"]),
            seeds=np.asarray(f["seeds"][()], dtype=np.float64).reshape(-1, len(variables)),
            starts=starts,
            best=[_read_best(f["best"][name], path) for name in sorted(f["best"])],
            trajectory=_text(f.attrs["trajectory"]),
            hertz_limit=scene_hertz_limit(scene),
            scene=scene,
        )


def soft_check_text(point: dict) -> str:
    """The soft-fraction re-check of a best point for a label ("" without one)."""
    if "soft_check_soft_fraction" not in point:
        return ""
    verdict = "" if point.get("soft_check_passed", 0) else ", FAILS the check"
    return (f"\nsoft fraction {point['soft_check_soft_fraction']:.3g} +- {point['soft_check_soft_fraction_stderr']:.2g}"
            f" (K = {int(point['soft_check_initial_conditions'])}){verdict}")


def hertz_text(opt: Optimisation) -> str:
    """The best point's Hertz validity as its re-solve from rest (the motion STEM_best.png
    shows) found it, e.g. "Hertz-valid: z_max/R* = 0.012 <= 0.05" or "Hertz-INVALID: z_max/R* =
    0.21 > 0.05"; "" without a best point."""
    if not opt.best:
        return ""
    z, valid = opt.best[0]["integrate_z_ratio"], bool(opt.best[0]["integrate_hertz_valid"])
    verdict = "Hertz-valid" if valid else "Hertz-INVALID (not a valid answer)"
    if not np.isfinite(z):
        return verdict
    if (z <= opt.hertz_limit) != valid:  # the file's flag against another limit: say only the ratio
        return f"{verdict}: z_max/R* = {z:.3g}"
    return f"{verdict}: z_max/R* = {z:.3g} {'<=' if valid else '>'} {opt.hertz_limit:g}"


def running_best(objective: np.ndarray, feasible: np.ndarray, sense: str) -> np.ndarray:
    """The best feasible objective after each evaluation (NaN before the first feasible one)."""
    out = np.full(objective.shape, np.nan)
    best = np.nan
    for i, (value, ok) in enumerate(zip(objective, feasible)):
        if ok and np.isfinite(value) and (np.isnan(best) or (value < best if sense == "minimise" else value > best)):
            best = value
        out[i] = best
    return out


def improving_points(start: Start, sense: str) -> np.ndarray:
    """Indices of the feasible evaluations that improved the start's best (its path)."""
    best = running_best(start.objective, start.feasible, sense)
    changed = np.concatenate(([True], best[1:] != best[:-1])) & np.isfinite(best)
    return np.nonzero(changed)[0]


def _seed_text(opt: Optimisation, s: Start) -> str:
    """The start's seed point, e.g. "m2=250, omega2=4.8" ("" when the file holds no such seed)."""
    if not 0 <= s.seed < len(opt.seeds):
        return ""
    return ", ".join(f"{name}={value:.4g}" for name, value in zip(opt.variables, opt.seeds[s.seed]))


def start_label(opt: Optimisation, s: Start) -> str:
    """A start's legend entry, distinct from every other start's: its number, algorithm, seed
    (number and point), contact law when it is free, best feasible value and why it stopped, e.g.
    "#0 bobyqa, seed 0 (m2=250, omega2=4.8): best 3, XTOL_REACHED"."""
    seed = _seed_text(opt, s)
    law = f", {s.law}" if s.law else ""
    best = f"best {s.objective[s.best]:.5g}" if s.best is not None and s.best < len(s.objective) else "no feasible point"
    stop = f", {s.stop}" if s.stop else ""
    return f"#{s.index} {s.algorithm}{law}, seed {s.seed}" + (f" ({seed})" if seed else "") + f": {best}{stop}"


def start_color(position: int) -> str:
    """One colour per start (matplotlib's ten-colour cycle, then tab20's lighter shades)."""
    return f"C{position}" if position < 10 else matplotlib.colormaps["tab20"]((2 * position + 1) % 20)


def contact_text(opt: Optimisation) -> str:
    """The contact law of the best point and its restitution, e.g. "contact: hunt-crossley,
    restitution e = 0.6": the best point's own (the file's best/00 law and restitution), else
    the scene's [contact] law and restitution; the defaults hertz and 1."""
    contact = scene_table(opt.scene, "contact")
    point = opt.best[0] if opt.best else {}
    law = str(point.get("law") or contact.get("law", "hertz"))
    e = point.get("restitution")
    if e is None:
        e = contact.get("restitution", 1.0)
    try:
        return f"contact: {law}, restitution e = {float(e):.4g}"
    except (TypeError, ValueError):
        return f"contact: {law}"


def plot_convergence(opt: Optimisation):
    """Objective against evaluation number, per start."""
    fig, ax = _figure.subplots(figsize=CONVERGENCE_FIGSIZE_IN, constrained_layout=True)
    shown = []
    for position, s in enumerate(opt.starts):
        color = start_color(position)
        number = np.arange(1, len(s.objective) + 1)
        ok = s.feasible & np.isfinite(s.objective)
        bad = ~s.feasible & np.isfinite(s.objective)
        ax.plot(number[ok], s.objective[ok], ".", color=color, alpha=0.35, markersize=4)
        ax.plot(number[bad], s.objective[bad], "x", color=INFEASIBLE_COLOR, markersize=4)
        ax.plot(number, running_best(s.objective, s.feasible, opt.sense), ALGORITHM_LINESTYLES.get(s.algorithm, "-"),
                color=color, linewidth=1.5, label=start_label(opt, s), gid=f"running-best-{s.index}")
        shown.append(s.objective[ok | bad])
    values = np.concatenate(shown) if shown else np.array([])
    values = values[np.isfinite(values) & (values > 0)]
    if values.size and values.max() / values.min() > LOG_RANGE:
        ax.set_yscale("log")
    if opt.best:
        level = opt.best[0].get("objective", np.nan)
        ax.axhline(level, color="k", linestyle="--", linewidth=0.8,
                   label=f"best {opt.quantity} = {level:.5g}{soft_check_text(opt.best[0])}")
    ax.set_xlabel("evaluation (point solves of the start, in order)")
    ax.set_ylabel(f"{opt.quantity} ({opt.sense}d)")
    ax.set_title(f"{os.path.basename(opt.path)}: convergence of {len(opt.starts)} start{'s' if len(opt.starts) != 1 else ''}, keeping {opt.regime}\n"
                 "dots: feasible evaluations; grey crosses: outside the kept regime; lines: best feasible so far",
                 fontsize=10)  # fmt: skip
    ax.grid(True, alpha=0.3)
    # Below the axes: the starts' labels are long, and beside them they would squeeze the axes.
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0.0, -0.13), borderaxespad=0.0, ncols=1 if len(opt.starts) < 8 else 2)
    return fig


def find_sibling(opt_path: str, name: str) -> str | None:
    """A file the optimisation names: as given (from the current directory), else beside OPT.h5."""
    if not name or name == "scene":
        return None
    for candidate in (name, os.path.join(os.path.dirname(os.path.abspath(opt_path)), os.path.basename(name))):
        if os.path.isfile(candidate):
            return candidate
    return None


def default_fix(opt: Optimisation, sweep, x: str, y: str | None, fixed: dict[str, float]) -> dict[str, float]:
    """--fix values, completed with the best point's values for the other map axes."""
    out = dict(fixed)
    if opt.best:
        for name in sweep.axis_names:
            if name not in (x, y) and name not in out and name in opt.best[0]:
                out[name] = opt.best[0][name]
    return out


def default_axes(opt: Optimisation, sweep, x: str | None, y: str | None) -> tuple[str, str | None]:
    """x and y: as given, else the map axes that are free parameters with the most grid points
    (ties in map order), else the map's first axes."""
    free = [name for name in sweep.axis_names if name in opt.variables] or sweep.axis_names
    free = sorted(free, key=lambda name: -len(sweep.axes[name].values))  # stable: ties keep map order
    if x is None:
        x = next((name for name in free if name != y), sweep.axis_names[0])
    if y is None:
        y = next((name for name in free if name != x), None)
        if y is None:
            y = next((name for name in sweep.axis_names if name != x), None)
    return x, y


def overlay_starts(ax, opt: Optimisation, x: str, y: str | None) -> list:
    """Each start's improving path from its seed, and the best points; returns legend handles."""
    cx, cy = opt.column(x), opt.column(y) if y is not None else None
    if cx is None:
        return []
    handles = []
    for s in opt.starts:
        path = improving_points(s, opt.sense)
        if path.size == 0:
            continue
        color = ALGORITHM_COLORS.get(s.algorithm, "C7")
        xs = s.x[path, cx]
        ys = s.x[path, cy] if cy is not None else np.full(xs.shape, 0.5)
        ax.plot(xs, ys, ALGORITHM_LINESTYLES.get(s.algorithm, "-"), color=color, linewidth=1.2, alpha=0.9,
                gid=f"path-{s.index}")
        ax.plot(xs[:1], ys[:1], SEED_MARKER, markerfacecolor="white", markeredgecolor=color, markersize=6)
    for algorithm in sorted({s.algorithm for s in opt.starts}):
        handles.append(Line2D([], [], color=ALGORITHM_COLORS.get(algorithm, "C7"), marker=SEED_MARKER,
                              linestyle=ALGORITHM_LINESTYLES.get(algorithm, "-"), markerfacecolor="white",
                              label=f"{algorithm}: seed and path"))  # fmt: skip
    for i, point in enumerate(opt.best):
        if x not in point or (y is not None and y not in point):
            continue
        px, py = point[x], point[y] if y is not None else 0.5
        ax.plot([px], [py], BEST_MARKER, color="gold", markeredgecolor="k", markersize=16, gid=f"best-{i}")
        ax.annotate(f"#{i}", (px, py), textcoords="offset points", xytext=(8, 6), fontsize=9)
    if opt.best:
        handles.append(Line2D([], [], linestyle="", marker=BEST_MARKER, color="gold", markeredgecolor="k",
                              markersize=12, label=f"best: {opt.quantity} = {opt.best[0].get('objective', np.nan):.5g}"))  # fmt: skip
    return handles


def plot_on_map(opt: Optimisation, sweep, x: str | None, y: str | None, fixed: dict[str, float]):
    """The regime map slice through the best point with the starts' paths and the best points."""
    x, y = default_axes(opt, sweep, x, y)
    sl = maps.choose_slice(sweep, x, y, default_fix(opt, sweep, x, y, fixed))
    fig = maps.plot(sweep, sl)
    ax = fig.axes[0]
    limits = ax.get_xlim(), ax.get_ylim()
    handles = overlay_starts(ax, opt, x, y)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    regime_legend = ax.get_legend()
    if handles:
        ax.add_artist(regime_legend)
        ax.legend(handles=handles, title="optimisation", loc="lower left", bbox_to_anchor=(1.01, 0.0),
                  borderaxespad=0.0, fontsize=8)  # fmt: skip
    ax.set_title(ax.get_title() + "\nstarts' paths and best points projected on this slice", fontsize=10)
    return fig, sl


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog=PROG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        description=__doc__,
        epilog=(
            "Writes STEM_convergence.png, STEM_on_map.png and STEM_best.png (STEM: -o without a trailing .png, "
            "default OPT without .h5). "
            "The map slice goes through the best point: map axes other than --x and --y are held at the grid "
            "values nearest to it (or --fix NAME=VALUE, SI units). Exit status 2 on a bad argument or file."
        ),
    )
    parser.add_argument("optimisation", metavar="OPT.h5", help="file written by vibromap optimise")
    parser.add_argument("--map", metavar="MAP.h5", help="seeding map (default: the file named in OPT.h5's seeds_from)")
    _args.add_slice(parser, x="map axis along x (default: the free parameter with the most grid points)",
                    y="map axis along y (default: the free parameter with the most points after x)",
                    fix="hold map axis NAME at the grid value nearest VALUE (default: the best point's value)")  # fmt: skip
    _args.add_periods(parser, "plot only N forcing periods of the best motion")
    _args.add_image(parser, "OPT without .h5", metavar="STEM",
                    what="stem of the images: STEM_convergence.png, STEM_on_map.png, STEM_best.png; "
                         "a trailing .png is dropped (-o law.png: law_convergence.png, ...)")  # fmt: skip
    args = _args.finish(parser, argv)
    args.output = output_stem(args.output, args.optimisation)
    return args


def output_stem(output: str | None, optimisation: str) -> str:
    """The images' stem: -o without a trailing .png (any case), else OPT without .h5."""
    if output is None:
        return os.path.splitext(optimisation)[0]
    root, ext = os.path.splitext(output)
    return root if ext.lower() == ".png" else output


def figure(path: str, show: str, x, y, fixed: dict, periods=None, map_path=None):
    """The figure of vibromap.plot.optimise: "convergence", "map" or "best"."""
    opt = read_optimise(path)
    if show == "convergence":
        return plot_convergence(opt)
    if show == "map":
        map_path = map_path or find_sibling(opt.path, opt.seeds_from)
        if map_path is None:
            raise VibromapFileError(f"{path}: no seeding map beside it (seeds from {opt.seeds_from or 'unknown'})")
        fig, sl = plot_on_map(opt, read_map(map_path), x, y, fixed)
        fig.vibromap_notes = maps.snapped_notes(sl)
        return fig
    traj_path = find_sibling(opt.path, opt.trajectory)
    if traj_path is None:
        raise VibromapFileError(f"{path}: no trajectory of the best point beside it")
    return best_figure(opt, read_trajectory(traj_path), periods)


def best_figure(opt: Optimisation, traj, periods):
    fig = plot_trajectory.plot(traj, plot_trajectory.select_periods(traj, periods))
    hertz = hertz_text(opt)
    fig.suptitle(f"best point: {plot_trajectory.title(traj)}\n{contact_text(opt)}" + (f"\n{hertz}" if hertz else ""))
    return fig


def write_figures(args: argparse.Namespace) -> tuple[list[str], list[str]]:
    """The figures that have their inputs: (files written, notes)."""
    opt = read_optimise(args.optimisation)
    written, notes = [], []
    out = f"{args.output}_convergence.png"
    save_figure(plot_convergence(opt), out, args.dpi)
    written.append(out)
    map_path = args.map or find_sibling(opt.path, opt.seeds_from)
    if map_path is None:
        notes.append(f"no seeding map (seeds from {opt.seeds_from or 'unknown'}; give --map): map figure skipped")
    else:
        fig, sl = plot_on_map(opt, read_map(map_path), args.x, args.y, args.fixed)
        out = f"{args.output}_on_map.png"
        save_figure(fig, out, args.dpi)
        written.append(out)
        notes.extend(maps.snapped_notes(sl))
    traj_path = find_sibling(opt.path, opt.trajectory)
    if traj_path is None:
        notes.append("no trajectory of the best point: best-point figure skipped")
    else:
        fig = best_figure(opt, read_trajectory(traj_path), args.periods)
        out = f"{args.output}_best.png"
        save_figure(fig, out, args.dpi)
        written.append(out)
    return written, notes


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    try:
        written, notes = write_figures(args)
    except (VibromapFileError, MapSliceError) as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    for note in notes:
        print(f"{PROG}: note: {note}")
    for path in written:
        print(f"{PROG}: wrote {path}")
    return 0


