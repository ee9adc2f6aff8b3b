"""Plot an orbit-diagram file of `vibromap orbit-diagram`: the stroboscopic x1 (or x2, v1, v2)
kept at each value of the stepped key, the upward sweep and the downward sweep in two colours,
so that hysteresis (the two differing over a range) and period doubling (a point splitting into
two) show.

  vibromap-post plot_orbit_diagram FILE.h5 [--var x1|x2|v1|v2] [-o FILE.png] [--dpi 150]

Exit status: 0 on success, 2 for a bad argument, an unreadable file or one of another format
version (one line on stderr), 3 when numpy, h5py or matplotlib cannot be imported (run via
vibromap-post).
"""

from __future__ import annotations

import argparse
import os
import sys

from .._guard import guarded_main

PROG = "plot_orbit_diagram"

import matplotlib
from . import _args, _figure
import numpy as np

from .._io import VibromapFileError, open_h5, read_dataset, write_plot, _text

COLOR_UP = "#1f77b4"
COLOR_DOWN = "#d62728"
UNITS = {"x1": "m", "x2": "m", "v1": "m/s", "v2": "m/s"}


def read_diagram(path: str, var: str):
    """(key name, units, values (steps,), states (2, steps, keep), key) or VibromapFileError."""
    with open_h5(path, "orbit-diagram file") as f:
        key = _text(f.attrs.get("key", ""))
        if not key or "direction" not in f or var not in f:
            raise VibromapFileError(f"{path}: not an orbit-diagram file of vibromap orbit-diagram (no key, direction or {var})")
        name = key.split(".")[-1]
        if name not in f:
            raise VibromapFileError(f"{path}: no coordinate '{name}' for the key {key}")
        values = np.asarray(read_dataset(f[name], path), dtype=float)
        states = np.asarray(read_dataset(f[var], path), dtype=float)
        if states.shape[:2] != (2, values.size):
            raise VibromapFileError(f"{path}: dataset '{var}' has shape {states.shape}, expected (2, {values.size}, keep)")
        return name, _text(f[name].attrs.get("units", "")), values, states, key


def plot(path: str, var: str):
    name, units, values, states, key = read_diagram(path, var)
    fig, ax = _figure.subplots(figsize=(9.0, 5.5), constrained_layout=True)
    keep = states.shape[2]
    for d, (color, label, marker) in enumerate(((COLOR_UP, "sweep up", "o"), (COLOR_DOWN, "sweep down", "x"))):
        x = np.repeat(values, keep)
        y = states[d].reshape(-1)
        ax.scatter(x, y, s=6 if d == 0 else 10, color=color, marker=marker, linewidths=0.8, label=label,
                   gid=f"orbit-diagram-{'up' if d == 0 else 'down'}")
    ax.set_xlabel(f"{key}, {units}" if units and units != "1" else key)
    ax.set_ylabel(f"stroboscopic {var}, {UNITS[var]}")
    ax.set_title(f"orbit diagram: {var} at the period starts after the transient  ({os.path.basename(path)})",
                 fontsize=10)
    ax.legend(loc="best", fontsize=9)
    return fig


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog=PROG, description="Plot a vibromap orbit-diagram file (sweep up and down).")
    parser.add_argument("file", help="orbit-diagram file (HDF5) of vibromap orbit-diagram -o")
    parser.add_argument("--var", choices=("x1", "x2", "v1", "v2"), default="x1", help="state to draw (default x1)")
    _args.add_image(parser, "FILE with .png")
    args = _args.finish(parser, argv, "file")
    from . import orbit_diagram

    return write_plot(PROG, lambda: orbit_diagram(args.file, args.var), args.output, args.dpi)


