"""Plot the regime map of a vibromap sweep: which motion each cell of a 2-D slice settles to.

Each distinct regime gets its own colour and a legend entry with its number of cells: the
periodic regimes (n,k) (the motion repeats after n forcing periods with k impacts in that
time; (1,1) is the paper's T-periodic one-blow motion), then chatter, no-contact,
permanent-contact, quasi-periodic, chaotic, non-periodic, unresolved, failed, and
not-computed for cells a partial run has not reached yet. Cells whose periodic orbit was found
unstable (its largest Floquet multiplier outside the unit circle; the map's stable == 0) are
hatched, with their count in the legend; so are, cross-hatched in red, the cells a map made with
analysis.fragility marks fragile (a perturbation of the initial state ends on another attractor:
the label is not an answer). Cells are drawn on their true edges
(in log space for a log axis, which is shown as log). A map with more than two axes is cut at
one grid value of every other axis (--fix, default the middle of the axis); the title names
those values, and, for a map made with analysis.steady = "shooting", that each cell is some
stable orbit, not necessarily the motion from rest. A 1-D map is drawn as a strip.

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid file (one line
on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import os
import sys

from .._guard import guarded_main

PROG = "plot_regime_map"

import matplotlib
import matplotlib.colors
import matplotlib.legend
import matplotlib.patheffects
from . import _args, _figure
import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from .._io import (NOT_COMPUTED, SOFT_FROM_MAP, STABLE_NO, MapAxis, MapSlice, MapSliceError, SoftInfo, SweepMap,
                   VibromapFileError, axis_name, cell_edges, read_curves, read_map, regime_counts,
                   slice2d, save_figure, write_plot)  # fmt: skip

FIGSIZE_IN = (9.0, 6.0)  # width, height in inches; at the default 150 dpi: 1350 x 900 px
STRIP_FIGSIZE_IN = (9.0, 3.0)  # a 1-D map: 1350 x 450 px
# Fixed colours for the regime kinds, so that maps from different runs read alike.
KIND_COLORS = {
    "chatter": "#d62728",  # red
    "no-contact": "#fff7bc",  # pale yellow: the bodies never touch
    "permanent-contact": "#8c564b",  # brown
    "quasi-periodic": "#e377c2",  # pink
    "chaotic": "#6a3d9a",  # deep purple
    "non-periodic": "#f4a6a6",  # light red
    "unresolved": "#7f7f7f",  # mid grey: the budget ran out
    "failed": "#000000",  # black: numerical failure
    NOT_COMPUTED: "#d9d9d9",  # light grey: not reached yet
}
# The periodic regimes (n,k) take these in order of n, then k: (1,1) is always the first.
PERIODIC_COLORS = (
    "#1f77b4", "#2ca02c", "#ff7f0e", "#17becf", "#bcbd22",
    "#aec7e8", "#98df8a", "#ffbb78", "#9edae5", "#dbdb8d",
)  # fmt: skip
OTHER_COLORS = ("#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173")  # labels of unknown codes
UNSTABLE_HATCH = "////"  # over the regime colour of cells whose periodic orbit is unstable
UNSTABLE_HATCH_COLOR = "0.15"
# Over the cells a map made with analysis.fragility marks fragile (a perturbation of the initial
# state ends on another attractor): their label is not an answer.
FRAGILE_HATCH = "xxx"
FRAGILE_HATCH_COLOR = "#d62728"
FRAGILE_GID = "fragile"
# Curves of `vibromap continue --curve` drawn over a map (--curves F.h5): a colour and line style
# per kind (plot_branch's colours for the bifurcations), level curves dashed, each level in a
# colour of its own; codimension-two points as markers, one marker per kind of point.
CURVE_STYLES = {"fold": ("#000000", "-"), "period-doubling": ("#ff7f0e", "-."), "neimark-sacker": ("#9467bd", ":"),
                "grazing": ("#2ca02c", (0, (6, 1.5, 1, 1.5, 1, 1.5)))}  # fmt: skip
LEVEL_COLORS = ("#e31a1c", "#1f78b4", "#b15928", "#6a3d9a", "#33a02c")
LEVEL_STYLE = "--"
OTHER_CURVE_STYLE = ("#7f7f7f", (0, (3, 1, 1, 1)))  # a kind this script does not know
CODIM2_MARKERS = ("o", "s", "D", "^", "v", "P", "X", "*")
CURVE_GID, CODIM2_GID = "curve", "codim2"  # gids of the curves' lines and of the codim-2 markers
CURVE_WIDTH = 1.8


def make_parser(prog: str = PROG, description: str | None = None, suffix: str = "_regime") -> argparse.ArgumentParser:
    """The options the map plots share (plot_kcon_map, plot_soft_map and plot_census_map add their
    own to this parser; description: their docstring)."""
    parser = argparse.ArgumentParser(
        prog=prog,
        # A script's own description is its module's docstring, laid out as written.
        formatter_class=argparse.RawDescriptionHelpFormatter if description else argparse.HelpFormatter,
        description=description
        or (
            "Plot the regime map of a 2-D slice of a vibromap map file: one colour per regime "
            "((1,1), (2,1), chatter, no-contact, ..., not-computed) with its cell count in the legend. "
            "(n,k) is a periodic motion repeating after n forcing periods with k impacts in that time; "
            "not-computed marks cells a partial (checkpointed) run has not reached. Log axes of the "
            "sweep are drawn as log axes."
        ),
        epilog=(
            "Axes are the swept parameters of the map (E1, E2, R1, R2, m2, k2, omega2, as stored). "
            "Axes other than --x and --y are held at one grid value: the one nearest to --fix NAME=VALUE "
            "(SI units, nearest in log space for a log axis), else the middle of the axis; the figure "
            "names the values used. A 1-D map is drawn as a strip. Exit status 2 on a bad argument or file."
        ),
    )
    parser.add_argument("map", metavar="MAP.h5", help="map file written by a vibromap sweep")
    _args.add_slice(
        parser,
        x="axis along x (default: the map's first axis)",
        y="axis along y (default: the map's first axis other than x; none for a 1-D map)",
        fix="hold axis NAME at the grid value nearest VALUE (SI units), e.g. --fix R1=0.5 m2=310; "
        "may be repeated; give MAP.h5 before it (default: the middle grid value of every axis not plotted)",
    )
    parser.add_argument(
        "--curves",
        metavar="F.h5",
        action="append",
        default=[],
        help="draw the curves of a curve file (vibromap continue --curve ... -o F.h5) over the map: one line "
        "style per kind, codim-2 points as markers; their two keys must be the plot's x and y axes (either way "
        "round); may be repeated",
    )
    _args.add_image(parser, f"MAP{suffix}.png")
    parser.add_argument(
        "--solved",
        action="store_true",
        help="an adaptive map (sweep.refine > 0): mark the points solved (computed == 1) with small dots and "
        "the audited ones (computed == 2) with crosses over the picture; the other points inherited their values",
    )
    return parser


def finish_args(parser: argparse.ArgumentParser, argv: list[str] | None, suffix: str) -> argparse.Namespace:
    """Parses argv, turns --fix into args.fixed {name: value}, defaults the output name."""
    return _args.finish(parser, argv, "map", suffix + ".png")


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    return finish_args(make_parser(), argv, "_regime")


def choose_slice(sweep: SweepMap, x: str | None, y: str | None, fixed: dict[str, float]) -> MapSlice:
    """slice2d with the scripts' defaults: x the first axis, y the first other axis (a strip
    for a 1-D map)."""
    names = sweep.axis_names
    x, y = axis_name(sweep, x), axis_name(sweep, y)
    if x is None:
        x = next((name for name in names if name != y), names[0])
    if y is None:
        y = next((name for name in names if name != x), None)
    return slice2d(sweep, x, y, fixed)


def snapped_notes(sl: MapSlice) -> list[str]:
    """One note per --fix value that is not itself a grid value."""
    notes = []
    for held in sl.fixed:
        if held.requested is not None and not np.isclose(held.requested, held.value, rtol=1e-9, atol=0.0):
            notes.append(f"{held.name} = {held.requested:.6g} is not a grid value; using {held.text()}")
    return notes


def soft_notes(info: SoftInfo) -> list[str]:
    """Notes on what the soft cells rest on when it is not the map's own /soft: computed for
    another soft_kcon, or a /soft cell overruled as Hertz-invalid."""
    notes = []
    if info.soft_source != SOFT_FROM_MAP:
        notes.append(f"soft cells {info.soft_source} ({info.definition()})")
    if info.overruled:
        notes.append(f"{cells_text(info.overruled)} the map calls soft are Hertz-invalid: shown as not soft")
    return notes


def label_colors(labels: list[str]) -> list[str]:
    """A colour per label: the fixed kind colours, the periodic palette in the given order."""
    colors, periodic, other = [], 0, 0
    for label in labels:
        if label in KIND_COLORS:
            colors.append(KIND_COLORS[label])
        elif label.startswith("("):
            colors.append(PERIODIC_COLORS[periodic % len(PERIODIC_COLORS)])
            periodic += 1
        else:
            colors.append(OTHER_COLORS[other % len(OTHER_COLORS)])
            other += 1
    return colors


def setup_axes(ax, sl: MapSlice):
    """Cell edges (x, y) for pcolormesh, log axes where the map's axes are log, axis labels.
    A strip (no y axis) spans y in [0, 1] without ticks."""
    x_edges = cell_edges(sl.x)
    ax.set_xlabel(sl.x.label())
    if sl.x.is_log:
        ax.set_xscale("log")
    if sl.x.categories:  # contact.law: one named column per law
        ax.set_xticks(sl.x.plot_values, sl.x.tick_labels())
    if sl.y is None:
        y_edges = np.array([0.0, 1.0])
        ax.set_yticks([])
    else:
        y_edges = cell_edges(sl.y)
        ax.set_ylabel(sl.y.label())
        if sl.y.is_log:
            ax.set_yscale("log")
        if sl.y.categories:
            ax.set_yticks(sl.y.plot_values, sl.y.tick_labels())
    return x_edges, y_edges


def slice_title(what: str, sweep: SweepMap, sl: MapSlice) -> str:
    """Two lines: what over which axes, then the fixed values (and whether the run is partial);
    a third for a map made by shooting, whose cells are not necessarily the motion from rest."""
    over = sl.x.name if sl.y is None else f"{sl.y.name} over {sl.x.name}"
    first = f"{what}: {over}  ({os.path.basename(sweep.path)})"
    second = f"fixed: {sl.fixed_text()}" if sl.fixed else "all axes shown"
    # From /done, not the attributes cells_done and complete: those are brought up to date only
    # when a run ends (a map still running, or killed, says 0).
    done, total = int(np.count_nonzero(sweep.data["done"])), int(np.asarray(sweep.data["done"]).size)
    if done < total:
        second += f";  partial run: {done} of {total} cells done"
    notes = [line for line in (sweep.answer_warning(), sweep.refine_note()) if line]
    return "\n".join([first, second] + notes)


def unstable_cells(sl: MapSlice) -> np.ndarray:
    """(ny, nx) mask of the cells done whose periodic orbit is unstable (stable == 0)."""
    return (np.asarray(sl.data["stable"]) == STABLE_NO) & (np.asarray(sl.data["done"]) != 0)


def fragile_cells(sl: MapSlice) -> np.ndarray | None:
    """(ny, nx) mask of the cells done marked fragile; None for a map made without analysis.fragility."""
    if "fragile" not in sl.data:
        return None
    return (np.asarray(sl.data["fragile"]) == 1) & (np.asarray(sl.data["done"]) != 0)


def draw_fragile(ax, sl: MapSlice, x_edges, y_edges) -> list:
    """Cross-hatches the fragile cells of a map made with analysis.fragility in red over their own
    colour; the legend entry (also for none: the map was assessed), or nothing for a map made without."""
    fragile = fragile_cells(sl)
    if fragile is None:
        return []
    if fragile.any():
        hatch_cells(ax, x_edges, y_edges, fragile, FRAGILE_HATCH, FRAGILE_HATCH_COLOR, gid=FRAGILE_GID)
    return [cell_patch("white", f"fragile (a perturbation ends elsewhere): {cells_text(int(fragile.sum()))}",
                       FRAGILE_HATCH, FRAGILE_HATCH_COLOR)]


def mask_rectangles(mask) -> list[tuple[int, int, int, int]]:
    """The cells of a (ny, nx) mask as few rectangles (j0, j1, i0, i1), rows j0..j1 - 1 and
    columns i0..i1 - 1: each row's runs of cells, a run merged with the same run of the rows
    below it. A refined map's hatched region is thousands of cells but tens of rectangles, and
    the renderer hatches each polygon on its own (9,094 cells took 3 s a draw)."""
    mask = np.asarray(mask, dtype=bool)
    open_runs: dict[tuple[int, int], int] = {}  # (i0, i1) -> first row
    out = []
    for j in range(mask.shape[0] + 1):
        runs = set()
        if j < mask.shape[0]:
            padded = np.concatenate(([False], mask[j], [False])).astype(np.int8)
            edges = np.flatnonzero(np.diff(padded))
            runs = {(int(a), int(b)) for a, b in zip(edges[0::2], edges[1::2])}
        for run in [r for r in open_runs if r not in runs]:
            out.append((open_runs.pop(run), j, run[0], run[1]))
        for run in runs:
            open_runs.setdefault(run, j)
    return sorted(out)


def hatch_cells(ax, x_edges, y_edges, mask, hatch=UNSTABLE_HATCH, color=UNSTABLE_HATCH_COLOR, face="none", gid=None):
    """Hatches the cells of `mask` (polygons over exactly those cells, mask_rectangles) in
    `color` over `face` ("none": the cell's own colour shows through); returns the PolyCollection."""
    quads = []
    for j0, j1, i0, i1 in mask_rectangles(mask):
        x0, x1, y0, y1 = x_edges[i0], x_edges[i1], y_edges[j0], y_edges[j1]
        quads.append([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    cells = PolyCollection(quads, facecolors=face, edgecolors=color, linewidths=0.0, hatch=hatch, gid=gid)
    ax.add_collection(cells, autolim=False)
    return cells


LEGEND_COLUMN_CHARS = 60  # longer labels than this get the legend row to themselves (one column)


def figure_with_legend_row(sl: MapSlice, figsize, strip_figsize):
    """(fig, ax, ax_legend): a figure of figsize (strip_figsize for a 1-D map), the map above a
    row of its own for the legend (legend_row fills it), so that constrained layout keeps the
    legend clear of the x label and the data (matplotlib < 3.7 does not lay out figure legends)."""
    fig, (ax, ax_legend) = _figure.subplots(2, 1, figsize=strip_figsize if sl.y is None else figsize, constrained_layout=True)
    ax_legend.axis("off")
    return fig, ax, ax_legend


def legend_row(fig, ax_legend, handles) -> None:
    """The legend in its row below the map: two columns, or one when a label is long, and the
    row as high as its lines (9-point text) need."""
    ncol = 2 if max(len(h.get_label()) for h in handles) <= LEGEND_COLUMN_CHARS else 1
    rows = -(-len(handles) // ncol)
    legend_in = 0.3 + 0.2 * rows
    ax_legend.get_gridspec().set_height_ratios([fig.get_figheight() - legend_in, legend_in])
    ax_legend.legend(handles=handles, loc="center", ncol=ncol, frameon=False, fontsize=9)


def cell_patch(color: str, label: str, hatch: str | None = None, hatch_color: str = UNSTABLE_HATCH_COLOR) -> Patch:
    """A legend entry for a kind of cell: its colour, its hatch if any, its label."""
    return Patch(facecolor=color, edgecolor=hatch_color if hatch else "0.4", hatch=hatch, linewidth=0.5, label=label)


def read_curve_files(paths: list[str]) -> list[tuple[str, list[dict]]]:
    """(path, read_curves(path)) of each --curves file, in the order given."""
    return [(os.fspath(path), read_curves(path)) for path in paths]


def axis_has_key(axis: MapAxis, key: str) -> bool:
    """Whether a map axis is the scene key (forcing.omega)."""
    return axis.key == key


def curve_swapped(sl: MapSlice, path: str, curve: dict) -> bool:
    """Whether the curve's (param, param2) are the plot's (y, x) rather than (x, y); an error
    naming the file, the curve's keys and the plot's axes when they are neither."""
    keys = (curve["param_name"], curve["param2_name"])
    shown = " and ".join(f"{axis.key} ({role})" for axis, role in ((sl.x, "x"), (sl.y, "y")) if axis)
    if sl.y is not None:
        if axis_has_key(sl.x, keys[0]) and axis_has_key(sl.y, keys[1]):
            return False
        if axis_has_key(sl.x, keys[1]) and axis_has_key(sl.y, keys[0]):
            return True
    raise VibromapFileError(f"{path}: {curve['group']} ({curve['kind']}) is a curve in {keys[0]} and {keys[1]}, but "
                            f"the plot's axes are {shown}; draw it over a map of these two keys (--x, --y)")  # fmt: skip


def curve_style(kind: str, levels: list[str]) -> tuple[str, object, str]:
    """(colour, line style, legend label) of a kind of curve; `levels` lists the level kinds met
    so far (each level takes the next of LEVEL_COLORS)."""
    if kind in CURVE_STYLES:
        return (*CURVE_STYLES[kind], f"{kind} curve")
    if kind.startswith("level:"):
        if kind not in levels:
            levels.append(kind)
        return LEVEL_COLORS[levels.index(kind) % len(LEVEL_COLORS)], LEVEL_STYLE, f"level curve {kind[len('level:'):]}"
    return (*OTHER_CURVE_STYLE, f"{kind} curve")


def codim2_kind(kind: str) -> str:
    """A codim-2 point's kind as one name whichever of its curves found it: the kinds that meet
    there in alphabetical order ("period-doubling+fold" and "fold+period-doubling" are one point,
    "fold+period-doubling")."""
    return "+".join(sorted(kind.split("+")))


def draw_curves(ax, sl: MapSlice, curve_files: list[tuple[str, list[dict]]], x_edges, y_edges) -> list:
    """Draws every curve of curve_files (read_curve_files) over the map, each a line (gid
    CURVE_GID) through its points, (param2, param) when the plot's axes are the other way round,
    and its codimension-two points as markers (gid CODIM2_GID, one Line2D per kind of point, as
    codim2_kind names it);
    keeps the axes on the map's extent, which clips them. Returns the legend entries: one per
    kind of curve and per kind of codim-2 point, in the order met."""
    handles: dict[str, Line2D] = {}
    levels: list[str] = []
    points: dict[str, list[tuple[float, float]]] = {}
    halo = [matplotlib.patheffects.withStroke(linewidth=CURVE_WIDTH + 1.6, foreground="white")]
    for path, curves in curve_files:
        for curve in curves:
            swapped = curve_swapped(sl, path, curve)
            x, y = (curve["param2"], curve["param"]) if swapped else (curve["param"], curve["param2"])
            color, style, label = curve_style(curve["kind"], levels)
            ax.plot(x, y, color=color, linestyle=style, linewidth=CURVE_WIDTH, path_effects=halo, gid=CURVE_GID,
                    zorder=3)  # fmt: skip
            handles.setdefault(label, Line2D([], [], color=color, linestyle=style, linewidth=CURVE_WIDTH, label=label))
            for point in curve["codim2"]:
                xy = (point["param2"], point["param"]) if swapped else (point["param"], point["param2"])
                points.setdefault(codim2_kind(point["kind"]), []).append(xy)
    for index, (kind, xy) in enumerate(points.items()):
        style = dict(linestyle="none", marker=CODIM2_MARKERS[index % len(CODIM2_MARKERS)], markersize=7,
                     markerfacecolor="white", markeredgecolor="black", markeredgewidth=1.2)  # fmt: skip
        ax.plot([p[0] for p in xy], [p[1] for p in xy], gid=CODIM2_GID, zorder=4, **style)
        handles[f"codim-2: {kind}"] = Line2D([], [], label=f"codim-2 point: {kind}", **style)
    if curve_files:
        ax.set_xlim(x_edges[0], x_edges[-1])
        ax.set_ylim(y_edges[0], y_edges[-1])
    return list(handles.values())


def plot(sweep: SweepMap, sl: MapSlice, curves=()):
    """The figure: one colour per regime label, legend entries 'label: count cells'; the curves of
    read_curve_files drawn over it (draw_curves) with theirs."""
    labels = sl.labels()
    counts = regime_counts(labels)
    categories = list(counts)
    colors = label_colors(categories)
    index = np.zeros(labels.shape, dtype=np.int64)
    for i, label in enumerate(categories):
        index[labels == label] = i
    cmap = matplotlib.colors.ListedColormap(colors)
    norm = matplotlib.colors.BoundaryNorm(np.arange(len(categories) + 1) - 0.5, len(categories))

    fig, ax = _figure.subplots(figsize=FIGSIZE_IN if sl.y is not None else STRIP_FIGSIZE_IN, constrained_layout=True)
    x_edges, y_edges = setup_axes(ax, sl)
    ax.pcolormesh(x_edges, y_edges, index, cmap=cmap, norm=norm, shading="flat")
    ax.set_title(slice_title("regime map", sweep, sl), fontsize=10)
    handles = [cell_patch(color, f"{label}: {cells_text(count)}")
               for label, color, count in zip(categories, colors, counts.values())]  # fmt: skip
    unstable = unstable_cells(sl)
    if unstable.any():
        hatch_cells(ax, x_edges, y_edges, unstable)
        handles.append(cell_patch("white", f"unstable orbit: {cells_text(int(unstable.sum()))}", UNSTABLE_HATCH))
    handles += draw_fragile(ax, sl, x_edges, y_edges)
    handles += draw_curves(ax, sl, list(curves), x_edges, y_edges)
    ax.legend(handles=handles, title="regime", loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    return fig


SOLVED_GID, AUDITED_GID = "solved-points", "audited-points"  # gids of the --solved markers (tests find them)
# computed code -> (gid, marker, size in points^2, colour, legend label)
SOLVED_MARKERS = ((1, SOLVED_GID, ".", 4.0, "black", "solved"), (2, AUDITED_GID, "x", 16.0, "#e7298a", "audited"))


def solved_points(sl: MapSlice, code: int) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) where the slice's /computed is `code`, at the points' own coordinates (a strip's
    points at y = 0.5)."""
    rows, cols = np.nonzero(np.asarray(sl.data["computed"]) == code)
    x = np.asarray(sl.x.plot_values, dtype=float)[cols]
    y = np.full(len(rows), 0.5) if sl.y is None else np.asarray(sl.y.plot_values, dtype=float)[rows]
    return x, y


def mark_solved(fig, sweep: SweepMap, sl: MapSlice) -> None:
    """--solved: dots on the points an adaptive map solved, crosses on the audited ones, over the
    map (the figure's first axes), with a legend of their counts beside the picture's own."""
    if "computed" not in sl.data:
        raise MapSliceError(f"{sweep.path}: no dataset 'computed': not an adaptive map (sweep.refine > 0), "
                            "so --solved has no solved points to draw")  # fmt: skip
    ax = fig.axes[0]
    handles = []
    for code, gid, marker, size, color, label in SOLVED_MARKERS:
        x, y = solved_points(sl, code)
        handles.append(ax.scatter(x, y, s=size, marker=marker, c=color, linewidths=0.8, gid=gid, zorder=3,
                                  label=f"{label}: {len(x)} point{'s' if len(x) != 1 else ''}"))  # fmt: skip
    # An artist of its own inside the map, so that the picture's legend (laid out beside the map)
    # stays where it is: a second ax.legend() would replace it.
    ax.add_artist(matplotlib.legend.Legend(ax, handles, [h.get_label() for h in handles], loc="lower right",
                                           fontsize=8, framealpha=0.85, title="adaptive map", title_fontsize=8))


def cells_text(count: int) -> str:
    return f"{count} cell{'s' if count != 1 else ''}"


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    from . import regime_map

    args = parse_args(argv)
    return write_map_figure(PROG, lambda: regime_map(args.map, args.x, args.y, args.fixed, args.curves, args.solved),
                            args.output, args.dpi)


def finish_map(fig, ax, ax_legend, sl: MapSlice, curves, handles: list, x_edges, y_edges):
    """A map picture's last layers: the fragile cells, the curves, the legend row of handles."""
    handles = handles + draw_fragile(ax, sl, x_edges, y_edges)
    handles += draw_curves(ax, sl, list(curves), x_edges, y_edges)
    legend_row(fig, ax_legend, handles)
    return fig


def write_map_figure(prog: str, make_figure, output: str, dpi: int) -> int:
    """A map script's end: write_plot with the figure's notes (vibromap_notes) printed."""
    notes = []

    def figure():
        fig = make_figure()
        notes.extend(fig.vibromap_notes)
        return fig

    return write_plot(prog, figure, output, dpi, (VibromapFileError, MapSliceError), notes)


