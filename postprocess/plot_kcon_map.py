#!/usr/bin/python3
"""Plot the impact softness k_con over a 2-D slice of a vibromap map, with the line where the
impact turns soft.

k_con = T / T_con (forcing period over the duration of the longest impact) is the source
paper's softness measure: near 1000 the impact is rigid (a short "stick"-shaped force pulse),
near 1-10 it is soft (a long "bell"). The heat map uses a log colour scale; cells without an
impact (no contact, or k_con not finite) and cells not computed are drawn in two greys and
named in the legend. A contour marks k_con = --threshold (default 10), the border between soft
(below) and rigid (above). Other axes are held fixed as in plot_regime_map (--fix); the title
names their values. The map must have stored k_con ([sweep] store = ["k_con", ...]).

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid file, or a map
without k_con (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run
via postprocess/vmpy).
"""

from __future__ import annotations

import sys

PROG = "plot_kcon_map"

from vibromap_deps import missing_module

try:
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed on a cluster node
    import matplotlib.colors
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    # vibromap_h5 (h5py) first, so that a missing module is reported under this script's name.
    from vibromap_h5 import MapSlice, MapSliceError, SweepMap, VibromapFileError, read_map, save_figure

    import plot_regime_map as maps
except ImportError as exc:
    missing_module(PROG, exc)

FIGSIZE_IN = (9.0, 6.5)  # width, height in inches; at the default 150 dpi: 1350 x 975 px
STRIP_FIGSIZE_IN = (9.0, 3.5)  # a 1-D map: 1350 x 525 px
CMAP = "viridis"  # dark = soft (small k_con), bright = rigid
COLOR_THRESHOLD = "#e31a1c"  # red: the soft/rigid border
COLOR_NO_IMPACT = "#9e9e9e"  # mid grey: computed, but no impact (k_con undefined)
COLOR_NOT_COMPUTED = "#dedede"  # light grey: not computed yet
THRESHOLD_GID = "k_con-threshold"  # gid of the threshold line collection (tests find it by this)


def parse_args(argv: list[str] | None):
    parser = maps.make_parser(
        prog=PROG,
        description=(
            "Plot k_con = T/T_con (forcing period over impact duration) over a 2-D slice of a vibromap "
            "map file, on a log colour scale, with the contour k_con = THRESHOLD where the impact turns "
            "soft. k_con ~1000 is a rigid impact, ~1-10 a soft one. Cells without an impact or not "
            "computed are grey. The map must store k_con ([sweep] store = [\"k_con\", ...])."
        ),
        suffix="_kcon",
    )
    parser.add_argument(
        "--threshold",
        metavar="K",
        type=float,
        default=10.0,
        help="draw the contour k_con = K, the soft/rigid border (default: 10; ~1000 is rigid, ~1-10 soft)",
    )
    args = maps.finish_args(parser, argv, "_kcon")
    if not (np.isfinite(args.threshold) and args.threshold > 0):
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


def _axis_coordinates(axis, values):
    """Coordinates in which contours are interpolated: log10 for a log axis, else the values."""
    return np.log10(values) if axis is not None and axis.is_log else np.asarray(values, dtype=np.float64)


def _from_coordinates(axis, u):
    return 10.0**u if axis is not None and axis.is_log else u


def threshold_segments(sl: MapSlice, k_con: np.ma.MaskedArray, threshold: float) -> list[np.ndarray]:
    """Polylines (arrays of (x, y) in data units) where k_con crosses `threshold`, interpolated
    linearly in log10(k_con) and in log10 of log axes (so that they sit right on log plots).
    A slice one cell high (a strip) gives vertical segments at the crossings along x, one cell
    wide horizontal segments at the crossings along y."""
    z = np.ma.log10(k_con)
    level = np.log10(threshold)
    u = _axis_coordinates(sl.x, sl.x.plot_values)
    if sl.y is None or z.shape[0] == 1:
        y_edges = maps.cell_edges(sl.y) if sl.y is not None else np.array([0.0, 1.0])
        return [
            np.array([[x, y_edges[0]], [x, y_edges[-1]]]) for x in _from_coordinates(sl.x, _crossings(u, z[0], level))
        ]
    v = _axis_coordinates(sl.y, sl.y.plot_values)
    if z.shape[1] == 1:
        x_edges = maps.cell_edges(sl.x)
        return [
            np.array([[x_edges[0], y], [x_edges[-1], y]]) for y in _from_coordinates(sl.y, _crossings(v, z[:, 0], level))
        ]
    segments = []
    for line in _contour_lines(u, v, z, level):
        if len(line) >= 2:
            segments.append(np.column_stack([_from_coordinates(sl.x, line[:, 0]), _from_coordinates(sl.y, line[:, 1])]))
    return segments


def _contour_lines(u, v, z, level):
    """Contour lines of z (masked, shape (len(v), len(u))) at `level`, in (u, v) coordinates."""
    try:
        import contourpy  # matplotlib >= 3.6 depends on it

        generator = contourpy.contour_generator(x=u, y=v, z=z, line_type=contourpy.LineType.Separate)
        return generator.lines(level)
    except ImportError:  # older matplotlib: contour on a throwaway figure
        fig, ax = plt.subplots()
        try:
            return ax.contour(u, v, z, levels=[level]).allsegs[0]
        finally:
            plt.close(fig)


def _crossings(u: np.ndarray, z: np.ma.MaskedArray, level: float) -> np.ndarray:
    """Positions along u where the 1-D masked z crosses `level` between neighbouring unmasked
    points (linear interpolation); a point exactly at the level counts once."""
    found = []
    for i in range(len(u) - 1):
        a, b = z[i], z[i + 1]
        if np.ma.is_masked(a) or np.ma.is_masked(b) or a == b or (a - level) * (b - level) > 0:
            continue
        found.append(u[i] + (level - a) / (b - a) * (u[i + 1] - u[i]))
    return np.unique(np.asarray(found, dtype=np.float64))


def plot(sweep: SweepMap, sl: MapSlice, threshold: float = 10.0):
    """The figure: log-coloured k_con, grey cells without impact or not computed, the contour
    k_con = threshold (a LineCollection with gid THRESHOLD_GID) and a colorbar."""
    k_con, no_impact, not_computed = kcon_cells(sl)
    strip = sl.y is None
    # The legend gets a row of its own below the plot, so that constrained layout keeps it clear
    # of the x label (matplotlib < 3.7 does not lay out figure legends).
    fig, (ax, ax_legend) = plt.subplots(
        2,
        1,
        figsize=STRIP_FIGSIZE_IN if strip else FIGSIZE_IN,
        constrained_layout=True,
        gridspec_kw={"height_ratios": [1.0, 0.16 if strip else 0.05]},
    )
    ax_legend.axis("off")
    x_edges, y_edges = maps.setup_axes(ax, sl)
    ax.set_title(maps.slice_title(f"k_con = T/T_con, soft below {threshold:g}", sweep, sl), fontsize=10)

    # Grey cells first: 0 = no impact, 1 = not computed, masked where k_con is shown.
    grey = np.ma.masked_array(not_computed.astype(np.int64), mask=~(no_impact | not_computed))
    grey_cmap = matplotlib.colors.ListedColormap([COLOR_NO_IMPACT, COLOR_NOT_COMPUTED])
    ax.pcolormesh(x_edges, y_edges, grey, cmap=grey_cmap, vmin=-0.5, vmax=1.5, shading="flat")

    handles = []
    if k_con.count() > 0:
        low, high = float(k_con.min()), float(k_con.max())
        if high <= low * 1.0000001:
            low, high = low / 2.0, high * 2.0
        cmap = plt.get_cmap(CMAP).copy()
        cmap.set_bad(alpha=0.0)  # masked cells: the grey layer below shows through
        mesh = ax.pcolormesh(
            x_edges, y_edges, k_con, cmap=cmap, norm=matplotlib.colors.LogNorm(low, high), shading="flat"
        )
        colorbar = fig.colorbar(mesh, ax=ax, pad=0.02)
        colorbar.set_label("k_con = T/T_con" if strip else "k_con = T/T_con  (~1000 rigid, ~1-10 soft)")
        if low <= threshold <= high:
            colorbar.ax.axhline(threshold, color=COLOR_THRESHOLD, linewidth=2.0)

        segments = threshold_segments(sl, k_con, threshold)
        if segments:
            lines = LineCollection(segments, colors=COLOR_THRESHOLD, linewidths=2.0, gid=THRESHOLD_GID)
            ax.add_collection(lines, autolim=False)
            label = f"k_con = {threshold:g}: soft where k_con < {threshold:g}, rigid above"
        else:
            side = "soft" if high < threshold else "rigid"
            label = f"k_con = {threshold:g} not crossed: all {side} here ({low:.3g} to {high:.3g})"
        handles.append(Line2D([], [], color=COLOR_THRESHOLD, linewidth=2.0, label=label))
    else:
        handles.append(Line2D([], [], color="none", label="no cell with an impact in this slice"))
    counts = ((no_impact, COLOR_NO_IMPACT, "no impact / no k_con"), (not_computed, COLOR_NOT_COMPUTED, "not computed"))
    for mask, color, what in counts:
        cells = int(mask.sum())
        if cells:
            plural = "s" if cells != 1 else ""
            handles.append(Patch(facecolor=color, edgecolor="0.4", linewidth=0.5, label=f"{what}: {cells} cell{plural}"))
    ax_legend.legend(handles=handles, loc="center", ncol=len(handles), frameon=False, fontsize=9)
    return fig


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    try:
        sweep = read_map(args.map)
        require_kcon(sweep)
        sl = maps.choose_slice(sweep, args.x, args.y, args.fixed)
        save_figure(plot(sweep, sl, args.threshold), args.output, args.dpi)
    except (VibromapFileError, MapSliceError) as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    for note in maps.snapped_notes(sl):
        print(f"{PROG}: note: {note}")
    print(f"{PROG}: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
