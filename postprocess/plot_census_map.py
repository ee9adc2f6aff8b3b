#!/usr/bin/python3
"""Plot a census map (a vibromap sweep whose scene had [census]): how many attractors each
cell holds, how much of each cell's box of initial states reaches a soft attractor, or the
basin fractions of one chosen cell.

  --show attractors   the number of attractors the census lists per cell (a discrete colour
                      per count); cells whose rest state reaches an attractor other than the
                      cell's largest basin are outlined
  --show soft         soft_fraction per cell: the total basin fraction of the attractors that
                      are soft (periodic with impacts, stable, Hertz-valid, k_con <= the map's
                      soft_kcon) (0..1)
  --show shock        per cell the minimal critical shock of its soft attractor (the soft one with
                      the largest basin fraction), in motion scales, on a log colour scale: how hard
                      a kick knocks the soft impact out; cells without a soft attractor grey, soft
                      attractors with no shock up to census.shock_max_radius dark (the map needs
                      census.shock = true)
A map made with analysis.steady = "shooting" says so in every picture's title.
  --show cell --at E1=1.4e10 E2=1e6
                      the basin fractions of the grid cell nearest those values, one bar per
                      attractor with its standard error, named by regime and k_con

Exit status: 0 on success, 2 for a bad argument, an unreadable file or a map without a
census (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via
postprocess/vmpy).
"""

from __future__ import annotations

import sys

PROG = "plot_census_map"

from vibromap_deps import missing_module

try:
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed on a cluster node
    import matplotlib.colors
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.patches import Patch

    from vibromap_h5 import (
        REGIME_PERIODIC,
        MapSliceError,
        SweepMap,
        VibromapFileError,
        parse_fix,
        read_map,
        write_plot,
    )

    import plot_regime_map as maps
except ImportError as exc:
    missing_module(PROG, exc)

FIGSIZE_IN = (9.0, 6.5)
COUNT_COLORS = ["#dedede", "#c6dbef", "#6baed6", "#2171b5", "#08306b", "#54278f", "#756bb1", "#9e9ac8", "#bcbddc"]
COLOR_NOT_COMPUTED = "#dedede"
COLOR_SOFT = "#1a9850"
COLOR_OTHER = "#4575b4"
COLOR_UNDECIDED = "#9e9e9e"
COLOR_NO_SHOCK = "#252525"
SUFFIX = {"attractors": "_attractors", "soft": "_soft", "shock": "_shock", "cell": "_cell"}


def parse_args(argv: list[str] | None):
    parser = maps.make_parser(
        prog=PROG,
        description=(
            "Plot a census map of vibromap (a sweep whose scene had [census]): the number of attractors "
            "per cell (--show attractors), the soft basin fraction per cell (--show soft), the soft "
            "attractor's minimal critical shock per cell (--show shock), or the basin "
            "fractions of one cell (--show cell --at NAME=VALUE ...)."
        ),
        suffix="_attractors",
    )
    parser.add_argument("--show", choices=("attractors", "soft", "shock", "cell"), default="attractors",
                        help="what to draw (default: attractors)")
    parser.add_argument("--at", metavar="NAME=VALUE", nargs="+", action="extend", default=[],
                        help="--show cell: the cell nearest these axis values (SI units; default: the middle of every axis)")
    args = parser.parse_args(argv)
    try:
        args.fixed = parse_fix(args.fix)
        args.at_values = parse_fix([a.replace("--fix", "--at") for a in args.at])
    except ValueError as exc:
        parser.error(str(exc).replace("--fix", "--at" if args.at else "--fix"))
    if args.dpi <= 0:
        parser.error("--dpi must be positive")
    if args.solved and args.show == "cell":
        parser.error("--solved marks the solved points of a map: not with --show cell")
    if args.curves and args.show == "cell":
        parser.error("--curves draws over a map: not with --show cell")
    if args.output is None:
        import os

        args.output = os.path.splitext(args.map)[0] + SUFFIX[args.show] + ".png"
    return args


def require_census(sweep: SweepMap) -> None:
    if not sweep.is_census:
        raise VibromapFileError(
            f"{sweep.path}: not a census map (no attractor datasets); sweep a scene with a [census] section"
        )


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


def add_soft_shock(sweep: SweepMap) -> None:
    """Adds to the map's per-cell data "soft_shock", the shock of each cell's soft attractor with
    the largest basin fraction (NaN where none was found), and "has_soft" (1 where the cell has a
    soft attractor), so that a slice carries them."""
    soft = np.asarray(sweep.census["soft"]) == 1
    fraction = np.where(soft, np.asarray(sweep.census["fraction"], dtype=float), -1.0)
    chosen = np.argmax(fraction, axis=-1)
    has_soft = soft.any(axis=-1) & (np.asarray(sweep.data["done"]) != 0)
    shock = np.take_along_axis(np.asarray(sweep.census["shock"], dtype=float), chosen[..., None], axis=-1)[..., 0]
    sweep.data["soft_shock"] = np.where(has_soft, shock, np.nan)
    sweep.data["has_soft"] = has_soft.astype(np.int8)


def draw_shock(fig, ax, sl, x_edges, y_edges):
    shock = np.asarray(sl.data["soft_shock"], dtype=float)
    has_soft = np.asarray(sl.data["has_soft"]) == 1
    found = has_soft & np.isfinite(shock) & (shock > 0)
    status = np.full(shock.shape, 0.0)  # 0 grey: no soft attractor (or not computed); 1 dark: no shock found
    status[has_soft & ~found] = 1.0
    ax.pcolormesh(x_edges, y_edges, status, cmap=matplotlib.colors.ListedColormap([COLOR_NOT_COMPUTED, COLOR_NO_SHOCK]),
                  vmin=0.0, vmax=1.0, shading="flat")
    handles = [Patch(facecolor=COLOR_NOT_COMPUTED, edgecolor="0.4", linewidth=0.5,
                     label=f"no soft attractor: {maps.cells_text(int((~has_soft).sum()))}")]
    if (has_soft & ~found).any():
        handles.append(Patch(facecolor=COLOR_NO_SHOCK, edgecolor="0.4", linewidth=0.5,
                             label=f"soft, no shock found: {maps.cells_text(int((has_soft & ~found).sum()))}"))
    if found.any():
        values = np.ma.masked_array(shock, mask=~found)
        lo, hi = float(values.min()), float(values.max())
        if hi <= lo:
            lo, hi = lo / 1.5, hi * 1.5
        mesh = ax.pcolormesh(x_edges, y_edges, values, cmap=plt.get_cmap("viridis"),
                             norm=matplotlib.colors.LogNorm(vmin=lo, vmax=hi), shading="flat")
        fig.colorbar(mesh, ax=ax, pad=0.02).set_label(
            "minimal critical shock of the soft attractor (motion scales L, omega L)", fontsize=9)
    title = f"soft attractor's critical shock: soft in {maps.cells_text(int(has_soft.sum()))}"
    if found.any():
        title += f", {float(shock[found].min()):.3g} .. {float(shock[found].max()):.3g}"
    return title, handles


def plot_map(sweep: SweepMap, sl, show: str, curves=()):
    done = np.asarray(sl.data["done"]) != 0
    fig, ax = plt.subplots(figsize=FIGSIZE_IN if sl.y is not None else maps.STRIP_FIGSIZE_IN, constrained_layout=True)
    x_edges, y_edges = maps.setup_axes(ax, sl)
    handles = []
    if show == "attractors":
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
        title, handles = draw_shock(fig, ax, sl, x_edges, y_edges)
    else:
        soft = np.ma.masked_array(np.asarray(sl.data["soft_fraction"], dtype=float), mask=~done)
        cmap = plt.get_cmap("viridis").copy()
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
    from vibromap_h5 import _nearest_index, axis_name

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
    fig, ax = plt.subplots(figsize=(9.0, 0.6 * len(labels) + 2.2), constrained_layout=True)
    y = np.arange(len(labels))[::-1]
    ax.barh(y, fractions, xerr=errors, color=colors, edgecolor="0.3", capsize=4)
    ax.set_yticks(y, labels)
    ax.set_xlim(0.0, 1.0)
    ax.set_xlabel("basin fraction (error bars: one standard error sqrt(p(1-p)/K))")
    for yy, f, e in zip(y, fractions, errors):
        ax.text(min(f + e + 0.02, 0.92), yy, f"{f:.3f}", va="center", fontsize=9)
    soft = float(sweep.data["soft_fraction"][index])
    warning = sweep.answer_warning()  # the from-rest attractor's datasets of a shooting map
    ax.set_title(f"basins of the cell {cell_text(sweep, index)}  ({sweep.path.rsplit('/', 1)[-1]})\n"
                 f"soft fraction {soft:.3f}; green: soft attractors" + (f"\n{warning}" if warning else ""), fontsize=10)
    return fig


def cell_text(sweep: SweepMap, index: tuple) -> str:
    return ", ".join(f"{name} = {axis.values[i]:.4g}" for (name, axis), i in zip(sweep.axes.items(), index))


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)

    def figure():
        sweep = read_map(args.map)
        require_census(sweep)
        if args.show == "shock":
            require_shock(sweep)
            add_soft_shock(sweep)
        if args.show == "cell":
            return plot_cell(sweep, cell_index(sweep, args.at_values))
        sl = maps.choose_slice(sweep, args.x, args.y, args.fixed)
        fig = plot_map(sweep, sl, args.show, maps.read_curve_files(args.curves))
        if args.solved:
            maps.mark_solved(fig, sweep, sl)
        return fig

    return write_plot(PROG, figure, args.output, args.dpi, (VibromapFileError, MapSliceError))


if __name__ == "__main__":
    sys.exit(main())
