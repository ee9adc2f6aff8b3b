"""Plot the "which law" chart: the effective restitution each contact law gives against the
restitution e it was calibrated for.

Input: the JSON of `vibromap restitution --format json` (src/cli/restitution_command.cpp), a
list of objects {law, e, chi, e_effective}, from a file or "-" for stdin. Each law's force is
K z^1.5 (1 + chi w / v_in) with chi calibrated from e; e_effective = |v_out / v_in| of one free
two-body impact. The figure: e_effective against e, one line per law, with the diagonal
e_effective = e where a law would give exactly what it was calibrated for; a second panel shows
the difference e_effective - e.

Exit status: 0 on success, 2 for a bad argument or an unreadable or invalid input (one line on
stderr), 3 when numpy or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from .._guard import guarded_main

PROG = "plot_restitution"

import matplotlib
from . import _args, _figure

FIGSIZE_IN = (9.0, 4.5)  # width, height in inches; at the default 150 dpi: 1350 x 675 px
FIELDS = ("law", "e", "chi", "e_effective")


class InputError(Exception):
    """A bad input file, reported as one line."""


def read_rows(path: str) -> dict[str, list[tuple[float, float]]]:
    """The (e, e_effective) points of each law, sorted by e, in the order the laws appear."""
    try:
        text = sys.stdin.read() if path == "-" else open(path, encoding="utf-8").read()
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror or exc})") from exc
    try:
        rows = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"{path}: not JSON ({exc})") from exc
    if not isinstance(rows, list) or not rows:
        raise InputError(f"{path}: expected a non-empty list of {{law, e, chi, e_effective}} objects")
    laws: dict[str, list[tuple[float, float]]] = {}
    for i, row in enumerate(rows):
        if not isinstance(row, dict) or any(f not in row for f in FIELDS):
            raise InputError(f"{path}: item {i} lacks one of {', '.join(FIELDS)}")
        e, e_eff = row["e"], row["e_effective"]
        if not all(isinstance(x, (int, float)) and math.isfinite(x) for x in (e, e_eff)):
            raise InputError(f"{path}: item {i} has a non-finite e or e_effective")
        laws.setdefault(str(row["law"]), []).append((float(e), float(e_eff)))
    for points in laws.values():
        points.sort()
    return laws


def make_figure(laws: dict[str, list[tuple[float, float]]]):
    fig, (ax, diff) = _figure.subplots(1, 2, figsize=FIGSIZE_IN, constrained_layout=True)
    ax.plot([0, 1], [0, 1], color="0.6", linestyle="--", linewidth=1, label="e_effective = e")
    diff.axhline(0.0, color="0.6", linestyle="--", linewidth=1)
    for law, points in laws.items():
        e = [p[0] for p in points]
        e_eff = [p[1] for p in points]
        ax.plot(e, e_eff, marker="o", markersize=4, label=law)
        diff.plot(e, [b - a for a, b in zip(e, e_eff)], marker="o", markersize=4, label=law)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_aspect("equal")
    ax.set_xlabel("target restitution e (calibration)")
    ax.set_ylabel("effective restitution |v_out / v_in|")
    ax.set_title("free two-body impact")
    ax.legend(fontsize="small")
    diff.set_xlim(0, 1)
    diff.set_xlabel("target restitution e")
    diff.set_ylabel("e_effective - e")
    diff.set_title("how far each law misses its target")
    return fig


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Plot the effective restitution of each contact law against its target e, from "
        "`vibromap restitution --format json`.",
    )
    parser.add_argument("input", help="JSON file of vibromap restitution --format json, or - for stdin")
    _args.add_image(parser, None, what="PNG file to write")
    args = _args.finish(parser, argv)
    try:
        laws = read_rows(args.input)
        fig = make_figure(laws)
        try:
            fig.savefig(args.output, dpi=args.dpi)
        except OSError as exc:
            raise InputError(f"{args.output}: cannot write ({exc.strerror or exc})") from exc
    except InputError as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    return 0


