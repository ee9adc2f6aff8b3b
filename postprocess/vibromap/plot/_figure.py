"""Figures made without pyplot, so that a picture function draws nothing on screen by itself,
leaves no figure open in pyplot's list and works on any backend (Agg included): a notebook
shows the Figure it returns; savefig writes it."""

from __future__ import annotations

import matplotlib
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure


def subplots(nrows: int = 1, ncols: int = 1, *, figsize, constrained_layout: bool = True, layout=None, **kwargs):
    """(figure, axes) as pyplot.subplots gives them, on a Figure of its own."""
    fig = Figure(figsize=figsize, layout=layout or ("constrained" if constrained_layout else None))
    FigureCanvasAgg(fig)  # a renderer for the pictures that measure their texts (plot_branch's labels)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def colormap(name: str):
    """A copy of the named colormap (set_bad and the like change the copy only)."""
    return matplotlib.colormaps[name].copy()
