"""Plot the impact softness k_con over a 2-D slice of a vibromap map, with the soft region
outlined.

k_con = T / T_con (forcing period over the duration of the longest impact) is the source
paper's softness measure: near 1000 the impact is rigid (a short "stick"-shaped force pulse),
near 1-10 it is soft (a long "bell"). The heat map uses a log colour scale; cells without a
k_con are drawn by why, each named in the legend with its count: no contact (mid grey),
permanent contact (brown), not periodic (quasi-periodic, chaotic, non-periodic: pink),
unresolved or failed (dark grey), any other without a finite k_con (tan), and not computed
(light grey). Cells beyond the Hertz limit (z_max/R* > the map's hertz_limit, 0.05 by
default) are greyed and hatched: their k_con comes from a force law that does not hold there.
A red line outlines the soft region by the one definition (periodic with impacts, stable,
Hertz-valid, k_con <= the map's soft_kcon): the map's /soft, or for another --threshold computed
from regime, stable, hertz_valid and k_con; an invalid cell is never inside it. A map made with
analysis.fragility cross-hatches its fragile cells in red (a perturbation of the initial state
ends on another attractor), as plot_regime_map does. Other axes are held fixed as in
plot_regime_map (--fix); the title names their values and, for a map made by shooting, that each
cell is some stable orbit, not necessarily the motion from rest. The map must have stored k_con ([sweep] store = ["k_con", ...]).

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid file, a map of
another format version or a map without k_con (one line on stderr), 3 when numpy, h5py or
matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import sys

from .._guard import guarded_main

PROG = "plot_kcon_map"

import matplotlib
import matplotlib.colors
from . import _figure
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D

from .._io import (FLAG_NO, FLAG_YES, HERTZ_KEY, SOFT_KEY, MapSlice, MapSliceError, SoftInfo, SweepMap,
                   VibromapFileError, add_soft_cells, cell_boundary, read_map, save_figure)  # fmt: skip

from . import _regime_map as maps

FIGSIZE_IN = (9.0, 6.5)  # width, height in inches; at the default 150 dpi: 1350 x 975 px
STRIP_FIGSIZE_IN = (9.0, 3.5)  # a 1-D map: 1350 x 525 px
CMAP = "viridis"  # dark = soft (small k_con), bright = rigid
COLOR_SOFT_OUTLINE = "#e31a1c"  # red: the border of the soft region
COLOR_NO_CONTACT = "#9e9e9e"  # mid grey: the bodies never touch (k_con undefined)
COLOR_NOT_COMPUTED = "#dedede"  # light grey: not computed yet
# Cells without a finite k_con, by why: (colour, legend text, regime flag meanings). A periodic
# cell with impacts always has one; "other" catches the rest (e.g. chatter without a k_con).
NO_KCON_KINDS = (
    (COLOR_NO_CONTACT, "no contact", ("no_contact",)),
    ("#8c564b", "permanent contact (no impact)", ("permanent_contact",)),
    ("#e377c2", "not periodic (quasi-periodic, chaotic): no k_con", ("quasi_periodic", "chaotic", "non_periodic")),
    ("#404040", "unresolved or failed: no k_con", ("unresolved", "failed")),
    ("#c49c94", "other: no finite k_con", ()),
)
HERTZ_HATCH = "xx"  # over Hertz-invalid cells, on a translucent white that greys their colour
HERTZ_HATCH_COLOR = "0.25"
HERTZ_FACE = (1.0, 1.0, 1.0, 0.55)
SOFT_GID = "soft-outline"  # gid of the soft region's outline (tests find it by this)
HERTZ_GID = "hertz-invalid"  # gid of the hatched Hertz-invalid cells
NO_KCON_GID = "no-kcon"  # gid of the cells drawn by why they have no k_con


def parse_args(argv: list[str] | None):
    parser = maps.make_parser(PROG, __doc__, "_kcon")
    parser.add_argument(
        "--threshold",
        metavar="K",
        type=float,
        default=None,
        help="soft means k_con <= K (default: the map's soft_kcon; another K "
        "recomputes the soft cells from regime, stable, Hertz validity and k_con; ~1000 is rigid, ~1-10 soft)",
    )
    args = maps.finish_args(parser, argv, "_kcon")
    if args.threshold is not None and not (np.isfinite(args.threshold) and args.threshold > 0):
        parser.error("--threshold must be a positive number")
    return args


def require_kcon(sweep: SweepMap) -> None:
    if "k_con" not in sweep.data:
        stored = " ".join(sweep.stored) or "none"
        raise VibromapFileError(
            f"{sweep.path}: the map did not store k_con (stored: {stored}); "
            'add "k_con" to the scene\'s [sweep] store list and rerun the sweep'
        )


def kcon_cells(sl: MapSlice):
    """(k_con with invalid cells masked, no-impact mask, not-computed mask), each (ny, nx)."""
    k_con = np.asarray(sl.data["k_con"], dtype=np.float64)
    not_computed = np.asarray(sl.data["done"]) == 0
    valid = ~not_computed & np.isfinite(k_con) & (k_con > 0)
    no_impact = ~not_computed & ~valid
    return np.ma.masked_array(k_con, mask=~valid), no_impact, not_computed


def no_kcon_kinds(sweep: SweepMap, sl: MapSlice, no_impact: np.ndarray) -> list[np.ndarray]:
    """The computed cells without a finite k_con split by why, one mask per NO_KCON_KINDS entry
    (by the cell's regime flag meaning; the last one takes every cell the others do not)."""
    regime = np.asarray(sl.data["regime"]) if "regime" in sl.data else np.full(no_impact.shape, -99)
    meaning = np.vectorize(lambda code: sweep.regime_meanings.get(int(code), ""), otypes=[str])(regime)
    masks, left = [], no_impact.copy()
    for _, _, meanings in NO_KCON_KINDS[:-1]:
        mask = left & np.isin(meaning, meanings)
        masks.append(mask)
        left &= ~mask
    return masks + [left]


def draw_kcon(fig, ax, x_edges, y_edges, k_con: np.ma.MaskedArray, soft_kcon: float, strip: bool) -> None:
    """k_con on a log colour scale (masked cells transparent) and its colorbar, with soft_kcon
    marked on the colorbar."""
    low, high = float(k_con.min()), float(k_con.max())
    if high <= low * 1.0000001:
        low, high = low / 2.0, high * 2.0
    cmap = _figure.colormap(CMAP)
    cmap.set_bad(alpha=0.0)  # masked cells: the grey layer below shows through
    mesh = ax.pcolormesh(x_edges, y_edges, k_con, cmap=cmap, norm=matplotlib.colors.LogNorm(low, high), shading="flat")
    colorbar = fig.colorbar(mesh, ax=ax, pad=0.02)
    colorbar.set_label("k_con = T/T_con" if strip else "k_con = T/T_con  (~1000 rigid, ~1-10 soft)")
    if low <= soft_kcon <= high:
        colorbar.ax.axhline(soft_kcon, color=COLOR_SOFT_OUTLINE, linewidth=2.0)


def soft_outline(ax, sl: MapSlice, info: SoftInfo, x_edges, y_edges):
    """Outlines the soft cells (data[SOFT_KEY] == 1: Hertz-valid ones only) along their edges, a
    LineCollection with gid SOFT_GID; returns its legend entry, which names the definition."""
    soft = np.asarray(sl.data[SOFT_KEY]) == FLAG_YES
    if not soft.any():
        return Line2D([], [], color="none", label=f"no soft cell here ({info.definition()})")
    segments = cell_boundary(soft, x_edges, y_edges)
    ax.add_collection(LineCollection(segments, colors=COLOR_SOFT_OUTLINE, linewidths=2.0, capstyle="projecting",
                                     gid=SOFT_GID), autolim=False)  # fmt: skip
    return Line2D([], [], color=COLOR_SOFT_OUTLINE, linewidth=2.0,
                  label=f"{info.definition()} (outlined): {maps.cells_text(int(soft.sum()))}")  # fmt: skip


def hertz_marks(ax, sl: MapSlice, info: SoftInfo, x_edges, y_edges):
    """Greys and hatches the Hertz-invalid cells (z_max/R* > hertz_limit: their k_con is computed
    beyond the force law's validity); returns the legend entry, with their count."""
    invalid = np.asarray(sl.data[HERTZ_KEY]) == FLAG_NO
    if invalid.any():
        maps.hatch_cells(ax, x_edges, y_edges, invalid, HERTZ_HATCH, HERTZ_HATCH_COLOR, HERTZ_FACE, HERTZ_GID)
    label = f"{info.invalid_text()}: {maps.cells_text(int(invalid.sum()))}"
    return maps.cell_patch(HERTZ_FACE, label, HERTZ_HATCH, HERTZ_HATCH_COLOR)


def plot(sweep: SweepMap, sl: MapSlice, info: SoftInfo, curves=()):
    """The figure: log-coloured k_con, cells without k_con coloured by why (NO_KCON_KINDS) or not computed, Hertz-invalid
    cells greyed and hatched, the soft region (add_soft_cells' flag: never an invalid cell)
    outlined (a LineCollection with gid SOFT_GID), a colorbar and a legend row below; the curves
    of maps.read_curve_files drawn over it (maps.draw_curves)."""
    k_con, no_impact, not_computed = kcon_cells(sl)
    fig, ax, ax_legend = maps.figure_with_legend_row(sl, FIGSIZE_IN, STRIP_FIGSIZE_IN)
    x_edges, y_edges = maps.setup_axes(ax, sl)
    ax.set_title(maps.slice_title("k_con = T/T_con, soft region outlined", sweep, sl), fontsize=10)

    # Cells without k_con first, one colour per reason (index into the list), not computed last;
    # masked where k_con is shown.
    counts = [(mask, color, what) for mask, (color, what, _) in zip(no_kcon_kinds(sweep, sl, no_impact), NO_KCON_KINDS)]
    counts.append((not_computed, COLOR_NOT_COMPUTED, "not computed"))
    reason = np.zeros(no_impact.shape, dtype=np.int64)
    for index, (mask, _, _) in enumerate(counts):
        reason[mask] = index
    reason_cmap = matplotlib.colors.ListedColormap([color for _, color, _ in counts])
    ax.pcolormesh(x_edges, y_edges, np.ma.masked_array(reason, mask=~(no_impact | not_computed)), cmap=reason_cmap,
                  vmin=-0.5, vmax=len(counts) - 0.5, shading="flat", gid=NO_KCON_GID)  # fmt: skip
    handles = []
    if k_con.count() > 0:
        draw_kcon(fig, ax, x_edges, y_edges, k_con, info.soft_kcon, sl.y is None)
    else:
        handles.append(Line2D([], [], color="none", label="no cell with an impact in this slice"))
    handles.append(soft_outline(ax, sl, info, x_edges, y_edges))
    handles.append(hertz_marks(ax, sl, info, x_edges, y_edges))
    for mask, color, what in counts:
        if mask.any():
            handles.append(maps.cell_patch(color, f"{what}: {maps.cells_text(int(mask.sum()))}"))
    return maps.finish_map(fig, ax, ax_legend, sl, curves, handles, x_edges, y_edges)


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    from . import kcon_map

    args = parse_args(argv)
    return maps.write_map_figure(PROG, lambda: kcon_map(args.map, args.x, args.y, args.fixed, args.curves, args.solved,
                                                        args.threshold), args.output, args.dpi)


