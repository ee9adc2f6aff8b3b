"""Plot where the motion of a vibromap map is soft, by the one definition vibromap uses
everywhere: periodic with impacts, stable, Hertz-valid (z_max/R* <= the map's hertz_limit,
0.05 by default) and k_con <= the map's soft_kcon (10 by default).

Each cell of a 2-D slice falls in the first category that applies, each with its own colour
and its cell count in the legend:
  not computed          cells a partial run has not reached
  Hertz-invalid         z_max/R* > hertz_limit: the force law does not hold, so the answer is
                        no answer (hatched); split into "would be soft" (stable, periodic with
                        impacts, k_con <= soft_kcon) and the rest
  soft                  the map's /soft
  rigid                 periodic with impacts, stable, Hertz-valid, k_con > soft_kcon
  unstable orbit        periodic with impacts, unstable; "stability unknown" where not computed
  no impact             no contact or permanent contact
  not periodic          chatter, quasi-periodic, chaotic, non-periodic, unresolved, failed
A map made with analysis.fragility cross-hatches its fragile cells in red (a perturbation of the
initial state ends on another attractor), as plot_regime_map does.
The title states the definition and, for a map made by shooting, that each cell is some stable
orbit, not necessarily the motion from rest. Axes and --fix work as in plot_regime_map.

Exit status: 0 on success, 2 for a bad argument, an unreadable or invalid file, or a map of
another format version (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported
(run via vibromap-post).
"""

from __future__ import annotations

import sys

from .._guard import guarded_main

PROG = "plot_soft_map"

import matplotlib
import matplotlib.colors
from . import _figure
import numpy as np

from .._io import (FLAG_NO, FLAG_YES, HERTZ_KEY, REGIME_PERIODIC, SOFT_KEY, STABLE_NO, STABLE_YES, MapSlice,
                   MapSliceError, SoftInfo, SweepMap, VibromapFileError, add_soft_cells, periodic_with_impacts,
                   read_map, write_plot)  # fmt: skip

from . import _regime_map as maps

FIGSIZE_IN = (9.0, 7.0)  # width, height in inches, legend row included; at 150 dpi: 1350 x 1050 px
STRIP_FIGSIZE_IN = (9.0, 4.0)  # a 1-D map: 1350 x 600 px
INVALID_HATCH, INVALID_HATCH_COLOR = "xx", "0.25"
# The categories in the order a cell is tested against them: (name, colour, hatch).
CATEGORIES = (
    ("not computed", "#dedede", None),
    ("Hertz-invalid, would be soft", "#a6dba0", INVALID_HATCH),
    ("Hertz-invalid", "#f6e8c3", INVALID_HATCH),
    ("soft", "#1a9850", None),
    ("rigid", "#4575b4", None),
    ("unstable orbit", "#c2a5cf", None),
    ("stability unknown", "#e7d4e8", None),
    ("no impact", "#fff7bc", None),
    ("not periodic", "#9e9e9e", None),
)
(NOT_COMPUTED, INVALID_SOFT, INVALID, SOFT, RIGID, UNSTABLE, UNKNOWN_STABILITY, NO_IMPACT,
 NOT_PERIODIC) = range(len(CATEGORIES))  # fmt: skip
ALWAYS_SHOWN = (SOFT, RIGID, INVALID_SOFT, INVALID)  # in the legend even with no cell
LEGEND_ORDER = ALWAYS_SHOWN + (UNSTABLE, UNKNOWN_STABILITY, NO_IMPACT, NOT_PERIODIC, NOT_COMPUTED)
NO_IMPACT_REGIMES = ("no_contact", "permanent_contact")


def parse_args(argv: list[str] | None):
    parser = maps.make_parser(PROG, __doc__, "_soft")
    return maps.finish_args(parser, argv, "_soft")


def classify(sl: MapSlice, info: SoftInfo) -> np.ndarray:
    """Each cell's category (an index into CATEGORIES): the first of them that applies. A
    Hertz-invalid cell is never soft, whatever the map's /soft says."""
    data = sl.data
    done = np.asarray(data["done"]) != 0
    soft = np.asarray(data[SOFT_KEY]) == FLAG_YES
    invalid = np.asarray(data[HERTZ_KEY]) == FLAG_NO
    periodic = periodic_with_impacts(data)
    stable = np.asarray(data["stable"])
    if "k_con" in data:
        k_con = np.asarray(data["k_con"], dtype=np.float64)
        would_be_soft = periodic & (stable == STABLE_YES) & (k_con > 0) & (k_con <= info.soft_kcon)
    else:
        would_be_soft = np.zeros(done.shape, dtype=bool)
    codes = [code for code, meaning in sl.regime_meanings.items() if meaning in NO_IMPACT_REGIMES]
    regime = np.asarray(data["regime"])
    no_impact = np.isin(regime, codes) | ((regime == REGIME_PERIODIC) & (np.asarray(data["k"]) == 0))
    conditions = [~done, invalid & would_be_soft, invalid, soft, periodic & (stable == STABLE_YES),
                  periodic & (stable == STABLE_NO), periodic, no_impact]  # fmt: skip
    return np.select(conditions, list(range(len(conditions))), NOT_PERIODIC)


def category_labels(info: SoftInfo, has_kcon: bool) -> list[str]:
    """The legend's name of each category, with the map's soft_kcon and hertz_limit."""
    invalid = info.invalid_text()
    labels = [name for name, _, _ in CATEGORIES]
    labels[INVALID_SOFT] = f"{invalid}, would be soft"
    labels[INVALID] = f"{invalid}, would not be soft either" if has_kcon else invalid
    labels[SOFT] = f"soft (k_con <= {info.soft_kcon:g})"
    labels[RIGID] = f"rigid: periodic with impacts, k_con > {info.soft_kcon:g}"
    labels[UNSTABLE] = "unstable periodic orbit"
    labels[UNKNOWN_STABILITY] = "periodic, stability unknown"
    labels[NO_IMPACT] = "no impact (no contact, permanent contact)"
    labels[NOT_PERIODIC] = "not periodic (chatter, chaotic, failed, ...)"
    return labels


def category_counts(category: np.ndarray) -> dict[int, int]:
    """Category index -> number of cells, for every category."""
    return {code: int((category == code).sum()) for code in range(len(CATEGORIES))}


def legend_handles(counts: dict[int, int], info: SoftInfo, has_kcon: bool) -> list:
    """One entry per category with cells (and always soft, rigid, Hertz-invalid), with its count."""
    labels = category_labels(info, has_kcon)
    shown = [code for code in LEGEND_ORDER if counts[code] or code in ALWAYS_SHOWN]
    if not has_kcon:  # "would be soft" cannot be told
        shown = [code for code in shown if code != INVALID_SOFT or counts[code]]
    handles = []
    for code in shown:
        _, color, hatch = CATEGORIES[code]
        handles.append(maps.cell_patch(color, f"{labels[code]}: {maps.cells_text(counts[code])}", hatch,
                                       INVALID_HATCH_COLOR))  # fmt: skip
    return handles


def caption(info: SoftInfo) -> str:
    """The definition, with the map's hertz_limit and soft_kcon."""
    return (f"soft = periodic with impacts, stable, Hertz-valid (z_max/R* <= {info.hertz_limit:g}) "
            f"and k_con <= {info.soft_kcon:g}")  # fmt: skip


def plot(sweep: SweepMap, sl: MapSlice, info: SoftInfo, curves=()):
    """The figure: one colour per category, the Hertz-invalid cells hatched, a legend row below
    with every category's cell count, the definition in the title; the curves of
    maps.read_curve_files drawn over it (maps.draw_curves)."""
    category = classify(sl, info)
    counts = category_counts(category)
    handles = legend_handles(counts, info, "k_con" in sl.data)
    fig, ax, ax_legend = maps.figure_with_legend_row(sl, FIGSIZE_IN, STRIP_FIGSIZE_IN)
    x_edges, y_edges = maps.setup_axes(ax, sl)
    cmap = matplotlib.colors.ListedColormap([color for _, color, _ in CATEGORIES])
    norm = matplotlib.colors.BoundaryNorm(np.arange(len(CATEGORIES) + 1) - 0.5, len(CATEGORIES))
    ax.pcolormesh(x_edges, y_edges, category, cmap=cmap, norm=norm, shading="flat")
    invalid = (category == INVALID_SOFT) | (category == INVALID)
    if invalid.any():
        maps.hatch_cells(ax, x_edges, y_edges, invalid, INVALID_HATCH, INVALID_HATCH_COLOR, gid="hertz-invalid")
    ax.set_title(maps.slice_title("where the motion is soft", sweep, sl) + "\n" + caption(info), fontsize=10)
    return maps.finish_map(fig, ax, ax_legend, sl, curves, handles, x_edges, y_edges)


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    from . import soft_map

    args = parse_args(argv)
    return maps.write_map_figure(PROG, lambda: soft_map(args.map, args.x, args.y, args.fixed, args.curves, args.solved),
                                 args.output, args.dpi)


