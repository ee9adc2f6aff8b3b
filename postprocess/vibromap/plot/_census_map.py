"""Plot a census map (a vibromap sweep whose scene had [census]): how many attractors each
cell holds, how much of each cell's box of initial states reaches a soft attractor, or the
basin fractions of one chosen cell.

  --show attractors   the number of attractors the census lists per cell (a discrete colour
                      per count); cells whose rest state reaches an attractor other than the
                      cell's largest basin are outlined
  --show soft         soft_fraction per cell: the total basin fraction of the attractors that
                      are soft (periodic with impacts, stable, Hertz-valid, k_con <= the map's
                      soft_kcon) (0..1)
  --show shock [--family ID]
                      per cell the minimal critical shock of one family's attractor (default: the
                      soft family, the one with the most soft cells), in motion scales, on a log
                      colour scale: how hard a kick knocks that motion out; cells without the family
                      grey, its attractors with no shock up to census.shock_max_radius dark, those
                      not searched (census.shock_soft_only) pale. A map without families (not
                      finished) shows each cell's soft attractor (the soft one with the largest
                      basin fraction). The map needs census.shock = true
A map made with analysis.steady = "shooting" says so in every picture's title.
  --show cell --at E1=1.4e10 E2=1e6
                      the basin fractions of the grid cell nearest those values, one bar per
                      attractor with its standard error, named by regime and k_con
  --show families     per cell the family of the attractor rest reaches (/family), the ten
                      largest families each a colour, the others grey; a dot marks cells where
                      that family changes its label (its regime differs from a matched neighbour's)
  --show family [--family ID]
                      the basin fraction of one family per cell (pale where the cell lacks it; the
                      cells where it changes label dotted); default: the family with the most
                      soft cells

Exit status: 0 on success, 2 for a bad argument, an unreadable file or a map without a
census (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via
vibromap-post).
"""

from __future__ import annotations

import os
import sys

from .._guard import guarded_main

PROG = "plot_census_map"

import matplotlib
import matplotlib.colors
import matplotlib.lines
from . import _args, _figure
import numpy as np
from matplotlib.patches import Patch

from .._io import (FAMILY_LABEL_CHANGE, REGIME_PERIODIC, MapSliceError, SweepMap, VibromapFileError, census_regimes,
                   parse_fix, read_map, write_plot)  # fmt: skip

from . import _regime_map as maps

FIGSIZE_IN = (9.0, 6.5)
COUNT_COLORS = ["#dedede", "#c6dbef", "#6baed6", "#2171b5", "#08306b", "#54278f", "#756bb1", "#9e9ac8", "#bcbddc"]
COLOR_NOT_COMPUTED = "#dedede"
COLOR_SOFT = "#1a9850"
COLOR_OTHER = "#4575b4"
COLOR_UNDECIDED = "#9e9e9e"
COLOR_NO_SHOCK = "#252525"
COLOR_NOT_SEARCHED = "#f3e6c4"  # the family is there, its shock was not looked for (census.shock_soft_only)
SUFFIX = {"attractors": "_attractors", "soft": "_soft", "shock": "_shock", "cell": "_cell", "families": "_families",
          "family": "_family"}
FAMILY_COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf",
                 "#393b79"]
COLOR_OTHER_FAMILY = "#a0a0a0"
COLOR_ABSENT = "#fbe3d6"


def parse_args(argv: list[str] | None):
    parser = maps.make_parser(PROG, __doc__, "_attractors")
    parser.add_argument("--show", choices=("attractors", "soft", "shock", "cell", "families", "family"), default="attractors",
                        help="what to draw (default: attractors)")
    parser.add_argument("--family", type=int, metavar="ID",
                        help="--show family, --show shock: the family's id (default: the family with the most soft cells)")
    parser.add_argument("--at", metavar="NAME=VALUE", nargs="+", action="extend", default=[],
                        help="--show cell: the cell nearest these axis values (SI units; default: the middle of every axis)")
    args = _args.finish(parser, argv)
    try:
        args.at_values = parse_fix([a.replace("--fix", "--at") for a in args.at])
    except ValueError as exc:
        parser.error(str(exc).replace("--fix", "--at"))
    if args.solved and args.show == "cell":
        parser.error("--solved marks the solved points of a map: not with --show cell")
    if args.curves and args.show == "cell":
        parser.error("--curves draws over a map: not with --show cell")
    if args.output is None:
        args.output = os.path.splitext(args.map)[0] + SUFFIX[args.show] + ".png"
    return args


def require_census(sweep: SweepMap) -> None:
    if not sweep.is_census:
        raise VibromapFileError(
            f"{sweep.path}: not a census map (no attractor datasets); sweep a scene with a [census] section"
        )


def require_families(sweep: SweepMap) -> np.ndarray:
    """The map's /family; refused when the family pass has not run (an unfinished map)."""
    family = sweep.census.get("family")
    if family is None or not (family >= 0).any():
        raise VibromapFileError(f"{sweep.path}: no families (the map is not finished, or made before families)")
    return family


def family_sizes(family: np.ndarray) -> np.ndarray:
    """Cells (entries) per family id."""
    return np.bincount(family[family >= 0].ravel(), minlength=int(family.max()) + 1)


def rest_family(sweep: SweepMap) -> tuple[np.ndarray, np.ndarray]:
    """Per cell the family of the attractor rest reaches (-1: none), and whether it changes
    label there."""
    family = require_families(sweep)
    from_rest = sweep.census["from_rest"] == 1
    flags = sweep.census["family_flags"]
    has = from_rest.any(axis=-1)
    at = np.argmax(from_rest, axis=-1)[..., None]
    fam = np.where(has, np.take_along_axis(family, at, -1)[..., 0], -1)
    change = has & ((np.take_along_axis(flags, at, -1)[..., 0] & FAMILY_LABEL_CHANGE) != 0)
    return fam, change


def default_family(sweep: SweepMap) -> int:
    """The family with the most soft entries (the most entries on ties; the largest family when
    none is soft)."""
    family = require_families(sweep)
    soft = np.bincount(family[(family >= 0) & (sweep.census["soft"] == 1)].ravel(), minlength=int(family.max()) + 1)
    sizes = family_sizes(family)
    return int(np.lexsort((-np.arange(len(sizes)), sizes, soft))[-1])


def family_fraction(sweep: SweepMap, chosen: int) -> tuple[np.ndarray, np.ndarray]:
    """Per cell the basin fraction of family `chosen` (NaN where the cell lacks it), and whether it
    changes label there."""
    family = require_families(sweep)
    if not 0 <= chosen <= int(family.max()):
        raise MapSliceError(f"{sweep.path}: no family {chosen} (ids 0..{int(family.max())})")
    mine = family == chosen
    fraction = np.where(mine, np.nan_to_num(sweep.census["fraction"]), 0.0).sum(axis=-1)
    fraction[~mine.any(axis=-1)] = np.nan
    change = (mine & ((sweep.census["family_flags"] & FAMILY_LABEL_CHANGE) != 0)).any(axis=-1)
    return fraction, change


def family_regimes(sweep: SweepMap, chosen: int) -> str:
    """The regimes family `chosen` has, e.g. "(1,1) no-contact"."""
    return census_regimes(sweep, sweep.census["family"] == chosen)


def mark_changes(ax, sl, change, x_edges, y_edges) -> list:
    """A dot at the centre of each cell of the slice where `change` holds."""
    if not change.any():
        return []
    xc = 0.5 * (np.asarray(x_edges)[1:] + np.asarray(x_edges)[:-1])
    yc = 0.5 * (np.asarray(y_edges)[1:] + np.asarray(y_edges)[:-1])
    rows, cols = np.nonzero(change)
    ax.plot(xc[cols], yc[rows], "o", color="black", markersize=3, linestyle="none")
    return [matplotlib.lines.Line2D([], [], marker="o", color="black", markersize=3, linestyle="none",
                                    label=f"label changes within the family: {maps.cells_text(int(change.sum()))}")]


def plot_families(sweep: SweepMap, sl, fig, ax, x_edges, y_edges) -> tuple[str, list]:
    done = np.asarray(sl.data["done"]) != 0
    fam = np.asarray(sl.data["_rest_family"])
    sizes = family_sizes(sweep.census["family"])
    top = [int(f) for f in np.argsort(-sizes, kind="stable")[: len(FAMILY_COLORS)] if sizes[f] > 0]
    code = np.full(fam.shape, len(top) + 1)  # other families
    code[~done | (fam < 0)] = 0
    for i, f in enumerate(top):
        code[fam == f] = i + 1
    colors = [COLOR_NOT_COMPUTED] + FAMILY_COLORS[: len(top)] + [COLOR_OTHER_FAMILY]
    cmap = matplotlib.colors.ListedColormap(colors)
    norm = matplotlib.colors.BoundaryNorm(np.arange(len(colors) + 1) - 0.5, len(colors))
    ax.pcolormesh(x_edges, y_edges, code, cmap=cmap, norm=norm, shading="flat")
    handles = []
    for i, f in enumerate(top):
        cells = int((code == i + 1).sum())
        if cells:
            handles.append(Patch(facecolor=colors[i + 1], edgecolor="0.4", linewidth=0.5,
                                 label=f"family {f} {family_regimes(sweep, f)}: {maps.cells_text(cells)}"))
    for value, what in ((len(top) + 1, "other families"), (0, "no attractor from rest, or not computed")):
        cells = int((code == value).sum())
        if cells:
            handles.append(Patch(facecolor=colors[value], edgecolor="0.4", linewidth=0.5,
                                 label=f"{what}: {maps.cells_text(cells)}"))
    handles += mark_changes(ax, sl, np.asarray(sl.data["_rest_change"]) & done, x_edges, y_edges)
    return f"family of rest's attractor ({len(sizes)} families in the map)", handles


def plot_family(sweep: SweepMap, sl, chosen: int, fig, ax, x_edges, y_edges) -> tuple[str, list]:
    done = np.asarray(sl.data["done"]) != 0
    values = np.asarray(sl.data["_family_fraction"], dtype=float)
    absent = done & np.isnan(values)
    fraction = np.ma.masked_array(values, mask=~done | absent)
    cmap = _figure.colormap("viridis")
    cmap.set_bad((0.0, 0.0, 0.0, 0.0))  # the layer below shows: not computed, or the family not there
    below = np.ma.masked_array(np.where(absent, 1, 0), mask=done & ~absent)
    ax.pcolormesh(x_edges, y_edges, below, cmap=matplotlib.colors.ListedColormap([COLOR_NOT_COMPUTED, COLOR_ABSENT]),
                  vmin=0, vmax=1, shading="flat")
    mesh = ax.pcolormesh(x_edges, y_edges, fraction, cmap=cmap, vmin=0.0, vmax=1.0, shading="flat")
    fig.colorbar(mesh, ax=ax, pad=0.02).set_label(f"basin fraction of family {chosen}", fontsize=9)
    handles = [Patch(facecolor=COLOR_ABSENT, edgecolor="0.4", linewidth=0.5,
                     label=f"family not there: {maps.cells_text(int(absent.sum()))}")]
    handles += mark_changes(ax, sl, np.asarray(sl.data["_family_change"]) & done, x_edges, y_edges)
    where = int((done & ~absent).sum())
    return f"family {chosen} ({family_regimes(sweep, chosen)}): in {maps.cells_text(where)}", handles


def attractor_label(sweep: SweepMap, index: tuple, a: int) -> str:
    """e.g. "(1,1) k_con 8.87 soft" or "non-periodic k_con 40.6 transient".

    "transient": states were seen to leave the non-periodic set (transient chaos).
    """
    c = sweep.census
    regime = int(c["regime"][index + (a,)])
    if regime == REGIME_PERIODIC:
        text = f"({int(c['n'][index + (a,)])},{int(c['k'][index + (a,)])})"
    else:
        text = sweep.regime_meanings.get(regime, str(regime)).replace("_", "-")
    k_con = float(c["k_con"][index + (a,)])
    if np.isfinite(k_con) and k_con > 0:
        text += f" k_con {k_con:.3g}"
    stable = int(c["stable"][index + (a,)])
    if stable == 0:
        text += " unstable"
    if int(c["soft"][index + (a,)]) == 1:
        text += " soft"
    if int(c["transient"][index + (a,)]) == 1:
        text += " transient"
    if int(c["from_rest"][index + (a,)]) == 1:
        text += " (from rest)"
    return text


def require_shock(sweep: SweepMap) -> None:
    if "shock" not in sweep.census:
        raise VibromapFileError(
            f"{sweep.path}: no shock datasets (attractor_shock); make the census map with census.shock = true"
        )


SHOCK_NOT_COMPUTED = 0  # /attractor_shock_status: ShockStatus::not_computed (census.shock_soft_only)


def add_shock(sweep: SweepMap, chosen: int | None) -> str:
    """Adds to the map's per-cell data "cell_shock", the shock of each cell's attractor of family
    `chosen` (without families: its soft attractor with the largest basin fraction; NaN where none
    was found), "has_it" (1 where the cell has that attractor) and "searched" (1 where its shock
    was looked for), so that a slice carries them. Returns what the attractor is, for the title."""
    done = np.asarray(sweep.data["done"]) != 0
    if chosen is None:
        mine = np.asarray(sweep.census["soft"]) == 1
        what = "the soft attractor"
    else:
        mine = np.asarray(sweep.census["family"]) == chosen
        what = f"family {chosen} {family_regimes(sweep, chosen)}"
    weight = np.where(mine, np.asarray(sweep.census["fraction"], dtype=float), -1.0)
    at = np.argmax(np.nan_to_num(weight, nan=-0.5), axis=-1)[..., None]
    has_it = mine.any(axis=-1) & done
    shock = np.take_along_axis(np.asarray(sweep.census["shock"], dtype=float), at, axis=-1)[..., 0]
    status = np.take_along_axis(np.asarray(sweep.census["shock_status"]), at, axis=-1)[..., 0]
    sweep.data["cell_shock"] = np.where(has_it, shock, np.nan)
    sweep.data["has_it"] = has_it.astype(np.int8)
    sweep.data["searched"] = (has_it & (status != SHOCK_NOT_COMPUTED)).astype(np.int8)
    return what


def shock_family(sweep: SweepMap, asked: int | None) -> int | None:
    """The family whose shock is drawn: the one asked, else the soft family; None for a map
    without families (each cell's soft attractor is drawn)."""
    family = sweep.census.get("family")
    if family is None or not (family >= 0).any():
        if asked is not None:
            require_families(sweep)
        return None
    if asked is not None and not 0 <= asked <= int(family.max()):
        raise MapSliceError(f"{sweep.path}: no family {asked} (ids 0..{int(family.max())})")
    return asked if asked is not None else default_family(sweep)


def draw_shock(fig, ax, sl, what: str, x_edges, y_edges):
    shock = np.asarray(sl.data["cell_shock"], dtype=float)
    has_it = np.asarray(sl.data["has_it"]) == 1
    searched = has_it & (np.asarray(sl.data["searched"]) == 1)
    found = searched & np.isfinite(shock) & (shock > 0)
    status = np.full(shock.shape, 0.0)  # 0 grey: not there; 1 pale: not searched; 2 dark: no shock found
    status[has_it & ~searched] = 1.0
    status[searched & ~found] = 2.0
    colors = [COLOR_NOT_COMPUTED, COLOR_NOT_SEARCHED, COLOR_NO_SHOCK]
    ax.pcolormesh(x_edges, y_edges, status, cmap=matplotlib.colors.ListedColormap(colors), vmin=-0.5, vmax=2.5,
                  shading="flat")
    handles = [Patch(facecolor=COLOR_NOT_COMPUTED, edgecolor="0.4", linewidth=0.5,
                     label=f"not there: {maps.cells_text(int((~has_it).sum()))}")]
    if (has_it & ~searched).any():
        handles.append(Patch(facecolor=COLOR_NOT_SEARCHED, edgecolor="0.4", linewidth=0.5,
                             label=f"not searched (not soft): {maps.cells_text(int((has_it & ~searched).sum()))}"))
    if (searched & ~found).any():
        handles.append(Patch(facecolor=COLOR_NO_SHOCK, edgecolor="0.4", linewidth=0.5,
                             label=f"no shock found: {maps.cells_text(int((searched & ~found).sum()))}"))
    if found.any():
        values = np.ma.masked_array(shock, mask=~found)
        lo, hi = float(values.min()), float(values.max())
        if hi <= lo:
            lo, hi = lo / 1.5, hi * 1.5
        mesh = ax.pcolormesh(x_edges, y_edges, values, cmap=_figure.colormap("viridis"),
                             norm=matplotlib.colors.LogNorm(vmin=lo, vmax=hi), shading="flat")
        fig.colorbar(mesh, ax=ax, pad=0.02).set_label("minimal critical shock (motion scales L, omega L)", fontsize=9)
    title = f"shock of {what}: found in {maps.cells_text(int(found.sum()))}"
    if found.any():
        title += f", {float(shock[found].min()):.3g} .. {float(shock[found].max()):.3g}"
    return title, handles


def plot_map(sweep: SweepMap, sl, show: str, curves=(), chosen: int | None = None, what: str = ""):
    done = np.asarray(sl.data["done"]) != 0
    fig, ax = _figure.subplots(figsize=FIGSIZE_IN if sl.y is not None else maps.STRIP_FIGSIZE_IN, constrained_layout=True)
    x_edges, y_edges = maps.setup_axes(ax, sl)
    handles = []
    if show == "families":
        title, handles = plot_families(sweep, sl, fig, ax, x_edges, y_edges)
    elif show == "family":
        title, handles = plot_family(sweep, sl, chosen, fig, ax, x_edges, y_edges)
    elif show == "attractors":
        count = np.where(done, np.asarray(sl.data["attractors"]), -1)
        top = max(int(count.max()), 1)
        colors = [COLOR_NOT_COMPUTED] + [COUNT_COLORS[1 + (i % (len(COUNT_COLORS) - 1))] for i in range(top + 1)]
        cmap = matplotlib.colors.ListedColormap(colors)
        norm = matplotlib.colors.BoundaryNorm(np.arange(-1, top + 2) - 0.5, len(colors))
        ax.pcolormesh(x_edges, y_edges, count, cmap=cmap, norm=norm, shading="flat")
        for value in range(-1, top + 1):
            cells = int((count == value).sum())
            if cells:
                what = "not computed" if value < 0 else f"{value} attractor{'s' if value != 1 else ''}"
                handles.append(Patch(facecolor=colors[value + 1], edgecolor="0.4", linewidth=0.5,
                                     label=f"{what}: {maps.cells_text(cells)}"))
        title = "attractors per cell (census)"
    elif show == "shock":
        title, handles = draw_shock(fig, ax, sl, what, x_edges, y_edges)
    else:
        soft = np.ma.masked_array(np.asarray(sl.data["soft_fraction"], dtype=float), mask=~done)
        cmap = _figure.colormap("viridis")
        cmap.set_bad(COLOR_NOT_COMPUTED)
        mesh = ax.pcolormesh(x_edges, y_edges, soft, cmap=cmap, vmin=0.0, vmax=1.0, shading="flat")
        fig.colorbar(mesh, ax=ax, pad=0.02).set_label("soft basin fraction (stable periodic with impacts, Hertz-valid, "
                                                      f"k_con <= {sweep.soft_kcon:g})", fontsize=9)
        robust = int((soft >= 0.9).sum())
        title = f"soft basin fraction (census); >= 0.9 in {maps.cells_text(robust)}"
        if (~done).any():
            title += f", not computed (grey): {maps.cells_text(int((~done).sum()))}"
    ax.set_title(maps.slice_title(title, sweep, sl), fontsize=10)
    handles += maps.draw_curves(ax, sl, list(curves), x_edges, y_edges)
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=9)
    return fig


def cell_index(sweep: SweepMap, at: dict[str, float]) -> tuple:
    from .._io import _nearest_index, axis_name

    at = {axis_name(sweep, name): value for name, value in at.items()}
    for name in at:
        if name not in sweep.axes:
            raise MapSliceError(f"{sweep.path}: no axis '{name}' for --at (axes: {', '.join(sweep.axes)})")
    return tuple(
        _nearest_index(axis, at[name]) if name in at else len(axis.values) // 2 for name, axis in sweep.axes.items()
    )


def plot_cell(sweep: SweepMap, index: tuple):
    if int(sweep.data["done"][index]) == 0:
        raise MapSliceError(f"{sweep.path}: the cell at {cell_text(sweep, index)} is not computed yet")
    count = int(sweep.data["attractors"][index])
    labels = [attractor_label(sweep, index, a) for a in range(count)]
    fractions = [float(sweep.census["fraction"][index + (a,)]) for a in range(count)]
    errors = [float(sweep.census["fraction_stderr"][index + (a,)]) for a in range(count)]
    colors = [COLOR_SOFT if int(sweep.census["soft"][index + (a,)]) == 1 else COLOR_OTHER for a in range(count)]
    for name, what in (("unresolved_fraction", "unresolved"), ("unlisted_fraction", "unlisted")):
        value = float(sweep.data[name][index])
        if value > 0:
            labels.append(what)
            fractions.append(value)
            errors.append(0.0)
            colors.append(COLOR_UNDECIDED)
    fig, ax = _figure.subplots(figsize=(9.0, 0.6 * len(labels) + 2.2), constrained_layout=True)
    y = np.arange(len(labels))[::-1]
    ax.barh(y, fractions, xerr=errors, color=colors, edgecolor="0.3", capsize=4)
    ax.set_yticks(y, labels)
    # Each fraction's number right of its error bar, never on it: the axis runs past 1 when a
    # bar and its error reach near 1, its ticks stay those of a fraction.
    ax.set_xlim(0.0, max([1.0] + [f + e + 0.1 for f, e in zip(fractions, errors)]))
    ax.set_xticks(np.linspace(0.0, 1.0, 6))
    ax.set_xlabel("basin fraction (error bars: one standard error sqrt(p(1-p)/K))")
    for yy, f, e in zip(y, fractions, errors):
        ax.text(f + e + 0.015, yy, f"{f:.3f}", va="center", fontsize=9)
    soft = float(sweep.data["soft_fraction"][index])
    warning = sweep.answer_warning()  # the from-rest attractor's datasets of a shooting map
    ax.set_title(f"basins of the cell {cell_text(sweep, index)}  ({sweep.path.rsplit('/', 1)[-1]})\n"
                 f"soft fraction {soft:.3f}; green: soft attractors" + (f"\n{warning}" if warning else ""), fontsize=10)
    return fig


def cell_text(sweep: SweepMap, index: tuple) -> str:
    return ", ".join(f"{name} = {axis.values[i]:.4g}" for (name, axis), i in zip(sweep.axes.items(), index))


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    from . import census_map

    args = parse_args(argv)
    return write_plot(PROG, lambda: census_map(args.map, args.show, args.x, args.y, args.fixed, args.curves, args.family,
                                               args.at_values, args.solved),
                      args.output, args.dpi, (VibromapFileError, MapSliceError))


def figure(path: str, show: str, x, y, fixed: dict, curves: list, family, at: dict, solved: bool):
    """The figure of --show SHOW (vibromap.plot.census_map)."""
    sweep = read_map(path)
    require_census(sweep)
    if show == "cell":
        return plot_cell(sweep, cell_index(sweep, at))
    chosen, what = None, ""
    if show == "families":  # per-cell arrays, sliced with the others
        sweep.data["_rest_family"], sweep.data["_rest_change"] = rest_family(sweep)
    elif show == "family":
        chosen = family if family is not None else default_family(sweep)
        sweep.data["_family_fraction"], sweep.data["_family_change"] = family_fraction(sweep, chosen)
    elif show == "shock":
        require_shock(sweep)
        chosen = shock_family(sweep, family)
        what = add_shock(sweep, chosen)
    sl = maps.choose_slice(sweep, x, y, fixed)
    fig = plot_map(sweep, sl, show, maps.read_curve_files(curves), chosen, what)
    if solved:
        maps.mark_solved(fig, sweep, sl)
    return fig


