"""Plot a basins file of `vibromap basins`: the plane of initial states coloured by the
attractor each one settles into (a distinct colour per attractor, grey for unresolved or
unlisted, white for overlapping bodies or pixels not computed), a legend naming each
attractor's regime, k_con, softness and basin fraction, the rest state marked, and a title
naming the scene's point, the fixed variables and the basin entropy (S_b, S_bb, the log 2 test
and the uncertainty exponent; absent from files made before vibromap computed it).

  vibromap-post plot_basins FILE.h5 [-o FILE.png] [--dpi 150]

Exit status: 0 on success, 2 for a bad argument or an unreadable file (one line on stderr),
3 when numpy, h5py or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import sys

from .._guard import guarded_main

PROG = "plot_basins"

import matplotlib
import matplotlib.colors
from . import _args, _figure
import numpy as np
from matplotlib.patches import Patch

from .._io import (
    BASINS_NOT_COMPUTED,
    BASINS_OVERLAP,
    BASINS_UNLISTED,
    BASINS_UNRESOLVED,
    Basins,
    read_basins,
    write_plot,
)

FIGSIZE_IN = (9.0, 6.5)
COLORS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22",
          "#393b79", "#637939", "#8c6d31"]
COLOR_UNDECIDED = "#9e9e9e"  # unresolved or unlisted
COLOR_BLANK = "#ffffff"  # overlap or not computed
POINT_KEYS = (("system", "m2", "m2 = {:g} kg"), ("system", "omega2", "omega2 = {:g} rad/s"),
              ("contact", "E1", "E1 = {:.3g} Pa"), ("contact", "E2", "E2 = {:.3g} Pa"),
              ("forcing", "omega", "omega = {:g} rad/s"))


def parse_args(argv: list[str] | None):
    p = argparse.ArgumentParser(prog=PROG, description="Plot the basins of attraction of a vibromap basins file.")
    p.add_argument("file", help="basins file (HDF5) of vibromap basins")
    _args.add_image(p, "FILE with .png")
    return _args.finish(p, argv, "file")


def legend_text(a) -> str:
    """'(1,1) k_con 8.96 soft: 52.3 %'"""
    kcon = f" k_con {a.k_con:.3g}" if np.isfinite(a.k_con) and a.k_con > 0 else ""
    kind = " soft" if a.soft else (" unstable" if a.stable == 0 else "")
    return f"{a.regime}{kcon}{kind}: {100 * a.fraction:.1f} %"


def scene_point(scene: str) -> str:
    """The scene's parameter point as 'm2 = 310 kg, ...' (the keys the scene gives)."""
    try:
        import tomllib

        data = tomllib.loads(scene)
    except Exception:  # an old Python or a scene the title need not understand
        return ""
    parts = [fmt.format(data[s][k]) for s, k, fmt in POINT_KEYS if isinstance(data.get(s, {}).get(k), (int, float))]
    return ", ".join(parts)


def entropy_text(b: Basins) -> str:
    """Two lines: 'S_b 0.0737, S_bb 0.501 (5 x 5 px boxes): S_bb <= ln 2 proves nothing' and the
    uncertainty exponent with its boundary dimension and fitted scales; '' for an older file."""
    e = b.entropy
    if e is None or not np.isfinite(e.S_b):
        return ""
    verdict = {"fractal": "S_bb > ln 2: fractal boundary", "not_shown": "S_bb <= ln 2 proves nothing",
               "no_boundary": "no boundary"}.get(e.log2_test, e.log2_test)
    alpha = (f"uncertainty exponent alpha {e.alpha:.3g}, boundary dimension {e.dimension:.3g} "
             f"(eps {e.fit_eps[0]}-{e.fit_eps[1]} px)" if np.isfinite(e.alpha) else "uncertainty exponent not fitted")
    return f"S_b {e.S_b:.3g}, S_bb {e.S_bb:.3g} ({e.box} x {e.box} px boxes): {verdict}\n{alpha}"


def colour_index(b: Basins) -> np.ndarray:
    """Index into the colour list: attractors 0..A-1, A undecided, A+1 blank."""
    A = len(b.attractors)
    idx = np.where(b.label >= 0, np.minimum(b.label, A), A + 1)
    idx = np.where((b.label == BASINS_UNRESOLVED) | (b.label == BASINS_UNLISTED), A, idx)
    idx = np.where((b.label == BASINS_OVERLAP) | (b.label == BASINS_NOT_COMPUTED), A + 1, idx)
    return idx


def plot(b: Basins):
    A = len(b.attractors)
    colours = [COLORS[i % len(COLORS)] for i in range(A)] + [COLOR_UNDECIDED, COLOR_BLANK]
    cmap = matplotlib.colors.ListedColormap(colours)
    fig, ax = _figure.subplots(figsize=FIGSIZE_IN, layout="constrained")
    ax.pcolormesh(b.x, b.y, colour_index(b), cmap=cmap, vmin=-0.5, vmax=A + 1.5, shading="nearest")
    names = ["x1", "x2", "v1", "v2"]
    rest = b.fixed_state
    ax.plot([rest[names.index(b.x_name)]], [rest[names.index(b.y_name)]], marker="*", markersize=14, color="k",
            markeredgecolor="w", linestyle="none", label="rest state")
    handles = [Patch(color=colours[i], label=legend_text(a)) for i, a in enumerate(b.attractors)]
    undecided = int(np.isin(b.label, [BASINS_UNRESOLVED, BASINS_UNLISTED]).sum())
    if undecided:
        handles.append(Patch(color=COLOR_UNDECIDED, label=f"unresolved or unlisted: {undecided} pixels"))
    handles += ax.get_legend_handles_labels()[0]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    ax.set_xlabel(f"initial {b.x_name} ({b.x_units})")
    ax.set_ylabel(f"initial {b.y_name} ({b.y_units})")
    point = scene_point(b.scene)
    title = "Basins of attraction" + ("" if b.complete else " (incomplete)") + (f"\n{point}" if point else "")
    entropy = entropy_text(b)
    ax.set_title(title + (f"\nfixed {b.fixed}" if b.fixed else "") + (f"\n{entropy}" if entropy else ""), fontsize=10)
    return fig


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    from . import basins

    return write_plot(PROG, lambda: basins(args.file), args.output, args.dpi)


