#!/usr/bin/python3
"""Plot a branch of `vibromap continue` (its -o HDF5 file, or its --format json output saved to a
file): the stroboscopic x1 of
the periodic orbit against the key, stable parts solid and unstable parts dashed, each located
bifurcation marked and named; over the orbit diagram of the same key when --diagram names an
orbit-diagram file (vibromap orbit-diagram -o).

  build/vibromap continue SCENE --param KEY --from A --to B -o branch.h5
  postprocess/vmpy plot_branch branch.h5 [--diagram od.h5] [-o branch.png] [--dpi 150]

Exit status: 0 on success, 2 for a bad argument or an unreadable file (one line on stderr),
3 when numpy, h5py or matplotlib cannot be imported (run via postprocess/vmpy).
"""

from __future__ import annotations

import argparse
import json
import os
import sys

PROG = "plot_branch"

from vibromap_deps import missing_module

try:
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed on a cluster node
    import matplotlib.pyplot as plt
    import numpy as np

    import plot_orbit_diagram
    from vibromap_h5 import VibromapFileError, _text, open_h5, read_dataset, write_plot
except ImportError as exc:
    missing_module(PROG, exc)

MARKERS = {"fold": ("o", "#000000"), "period-doubling": ("s", "#ff7f0e"), "neimark-sacker": ("D", "#9467bd"),
           "grazing": ("v", "#2ca02c")}


BIFURCATION_TYPES = ("fold", "period-doubling", "neimark-sacker", "grazing")  # flag values 0..3 of the file


def read_branch_file(path: str) -> dict:
    """A branch file (HDF5, include/vibromap/io/branch_file.hpp) as the JSON's structure: the first
    branch's points and bifurcations at the top, the switched branches under "branches"."""
    with open_h5(path) as f:
        if "param" not in f or "bifurcation_type" not in f or "key" not in f.attrs:
            raise VibromapFileError(f"{path}: not a branch file of vibromap continue (no param, bifurcation_type or key)")
        names = ["param", "stable", "x1", "x2", "v1", "v2", "bifurcation_type", "bifurcation_param",
                 "bifurcation_x1", "bifurcation_x2", "bifurcation_v1", "bifurcation_v2"]
        names += [n for n in ("point_branch", "bifurcation_branch", "strobe_x1", "branch_n", "branch_parent",
                              "branch_born_at") if n in f]
        get = {name: np.asarray(read_dataset(f[name], path)) for name in names}
        data = {"key": _text(f.attrs["key"]), "n": int(f.attrs.get("n", 1)), "stop": _text(f.attrs.get("stop", ""))}
        stops = _text(f.attrs.get("stops", data["stop"])).split("\n")
    count = len(get["param"])
    owner = get.get("point_branch", np.zeros(count, dtype=int))
    bif_owner = get.get("bifurcation_branch", np.zeros(len(get["bifurcation_type"]), dtype=int))
    ns = get.get("branch_n", np.array([data["n"]]))

    def points(k):
        out = []
        for i in np.flatnonzero(owner == k):
            p = {"param": float(get["param"][i]), "stable": bool(get["stable"][i]),
                 "y": [float(get[c][i]) for c in ("x1", "x2", "v1", "v2")]}
            if "strobe_x1" in get:
                p["strobe_x1"] = [float(x) for x in get["strobe_x1"][i] if np.isfinite(x)]
            out.append(p)
        return out

    def bifurcations(k):
        return [{"type": BIFURCATION_TYPES[int(get["bifurcation_type"][i])], "param": float(get["bifurcation_param"][i]),
                 "y": [float(get["bifurcation_" + c][i]) for c in ("x1", "x2", "v1", "v2")]}
                for i in np.flatnonzero(bif_owner == k)]

    data["points"], data["bifurcations"] = points(0), bifurcations(0)
    data["branches"] = [{"n": int(ns[k]), "parent": int(get["branch_parent"][k]), "born_at": int(get["branch_born_at"][k]),
                         "stop": stops[k] if k < len(stops) else "", "points": points(k), "bifurcations": bifurcations(k)}
                        for k in range(1, len(ns))]
    return data


def read_branch(path: str):
    """A branch from an HDF5 branch file or from a saved --format json output."""
    try:
        with open(path, "rb") as f:
            if f.read(8) == b"\x89HDF\r\n\x1a\n":
                return read_branch_file(path)
    except OSError as exc:
        raise VibromapFileError(f"{path}: cannot read ({exc.strerror or exc})") from exc
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except OSError as exc:
        raise VibromapFileError(f"{path}: cannot read ({exc.strerror or exc})") from exc
    except json.JSONDecodeError as exc:
        raise VibromapFileError(f"{path}: not JSON ({exc.msg} at line {exc.lineno})") from exc
    if not isinstance(data, dict) or "points" not in data or "key" not in data:
        raise VibromapFileError(f"{path}: not a branch of vibromap continue --format json (no key or points)")
    return data


def segments(params, x1, stable):
    """Runs of consecutive points of equal stability, each including the point where it changes."""
    runs, start = [], 0
    for i in range(1, len(params) + 1):
        if i == len(params) or stable[i] != stable[start]:
            end = min(i + 1, len(params))
            runs.append((params[start:end], x1[start:end], stable[start]))
            start = i
    return runs


SWITCHED_COLORS = ("#d62728", "#8c564b", "#e377c2", "#17becf", "#bcbd22")


def strobe_x1(point: dict) -> list:
    """x1 at the period starts of a point's cycle (the state's x1 alone when not given)."""
    return point.get("strobe_x1") or [point["y"][0]]


def draw_branch(ax, branch: dict, gid: str, color: str, shown: set, name: str = "branch", annotate: bool = True):
    """One branch: each period start's x1 against the key (a period-n branch draws n curves),
    stable solid and unstable dashed, its bifurcations marked at their own states (and their key
    values written next to them when `annotate`)."""
    points = branch["points"]
    if not points:
        return
    params = np.array([p["param"] for p in points])
    stable = [bool(p["stable"]) for p in points]
    n = min(len(strobe_x1(p)) for p in points)
    for k in range(n):
        x1 = np.array([strobe_x1(p)[k] for p in points])
        for xs, ys, st in segments(params, x1, stable):
            label = f"{name}, {'stable' if st else 'unstable'}"
            ax.plot(xs, ys, "-" if st else "--", color=color, linewidth=1.6 if gid == "branch" else 1.2,
                    label=None if label in shown else label, gid=f"{gid}-{'stable' if st else 'unstable'}")
            shown.add(label)
    for b in branch.get("bifurcations", []):
        marker, mcolor = MARKERS.get(b["type"], ("x", "#d62728"))
        y = b["y"][0]  # the located point's own state (the branch may pass the parameter more than once)
        ax.scatter([b["param"]], [y], marker=marker, s=45, color=mcolor, zorder=5,
                   label=None if b["type"] in shown else b["type"], gid=f"bifurcation-{b['type']}")
        shown.add(b["type"])
        if annotate:
            ax.annotate(f"{b['param']:.4f}", (b["param"], y), textcoords="offset points", xytext=(4, 4), fontsize=7)


def plot(branch: dict, diagram: str | None = None):
    fig, ax = plt.subplots(figsize=(9.0, 5.5), constrained_layout=True)
    if diagram:
        name, units, values, states, key = plot_orbit_diagram.read_diagram(diagram, "x1")
        keep = states.shape[2]
        for d, color in enumerate(("#9ecae1", "#fcbba1")):
            ax.scatter(np.repeat(values, keep), states[d].reshape(-1), s=4, color=color,
                       label=f"orbit diagram, sweep {'up' if d == 0 else 'down'}")
    shown = set()
    draw_branch(ax, branch, "branch", "#08306b", shown)
    for k, switched in enumerate(branch.get("branches", []), start=1):
        n = switched.get("n", 2)
        generation = max(int(n // branch.get("n", 1)).bit_length() - 2, 0)
        draw_branch(ax, switched, f"branch{k}", SWITCHED_COLORS[generation % len(SWITCHED_COLORS)], shown,
                    f"period-{n} branches", annotate=False)
    ax.set_xlabel(branch["key"])
    ax.set_ylabel("x1 at the period start, m")
    switched = branch.get("branches", [])
    ax.set_title(f"branch of the period-{branch.get('n', 1)} orbit ({len(branch['points'])} points, "
                 f"{len(branch.get('bifurcations', []))} bifurcations): {branch.get('stop', '')}"
                 + (f"; {len(switched)} switched at period doublings" if switched else ""), fontsize=10)
    ax.legend(loc="best", fontsize=7, ncol=2)
    return fig


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog=PROG, description="Plot a branch of vibromap continue.")
    parser.add_argument("branch", help="branch file of vibromap continue -o (HDF5), or its --format json output")
    parser.add_argument("--diagram", help="orbit-diagram file (HDF5) of the same key to draw underneath")
    parser.add_argument("-o", "--output", help="PNG to write (default: BRANCH with .png)")
    parser.add_argument("--dpi", type=int, default=150, help="resolution, dots per inch (default 150)")
    args = parser.parse_args(argv)
    if args.dpi <= 0:
        parser.error("--dpi must be positive")
    output = args.output or os.path.splitext(args.branch)[0] + ".png"
    return write_plot(PROG, lambda: plot(read_branch(args.branch), args.diagram), output, args.dpi)


if __name__ == "__main__":
    sys.exit(main())
