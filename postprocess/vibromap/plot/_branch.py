"""Plot a branch of `vibromap continue` (its -o HDF5 file, or its --format json output saved to a
file): the stroboscopic x1 of the periodic orbit against the key (with its unit), stable parts
solid and unstable parts dashed, each located bifurcation marked; over the orbit diagram of the
same key when --diagram names an orbit-diagram file (vibromap orbit-diagram -o). Above it, a
strip names each bifurcation of the first branch by its key value, the labels spread apart so
that none overlaps another, each joined by a leader to its key value; below it, a panel of the
softness k_con = T/T_con along every branch with the soft threshold analysis.soft_kcon (from the
file's scene, 10 when it does not say).

  build/vibromap continue SCENE --param KEY --from A --to B -o branch.h5
  vibromap-post plot_branch branch.h5 [--diagram od.h5] [-o branch.png] [--dpi 150]

Exit status: 0 on success, 2 for a bad argument or an unreadable file (one line on stderr),
3 when numpy, h5py or matplotlib cannot be imported (run via vibromap-post).
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import textwrap

from .._guard import guarded_main

PROG = "plot_branch"

import matplotlib
from . import _args, _figure
import numpy as np

from . import _orbit_diagram as plot_orbit_diagram
from .._io import VibromapFileError, _text, open_h5, read_dataset, write_plot

MARKERS = {"fold": ("o", "#000000"), "period-doubling": ("s", "#ff7f0e"), "neimark-sacker": ("D", "#9467bd"),
           "grazing": ("v", "#2ca02c")}


BIFURCATION_TYPES = ("fold", "period-doubling", "neimark-sacker", "grazing")  # flag values 0..3 of the file

# The unit of each numeric scene key a branch can follow, as `vibromap keys` (jobs/reference.toml)
# gives them ("1": dimensionless): for a saved --format json, which does not carry the unit (the
# HDF5 file does: its `units` attribute).
KEY_UNITS = {
    "system.m1": "kg", "system.m2": "kg", "system.k1": "N/m", "system.omega1": "rad/s", "system.k2": "N/m",
    "system.omega2": "rad/s", "system.xi1": "1", "system.c1": "N s/m", "system.xi2": "1", "system.c2": "N s/m",
    "system.D": "m", "contact.E1": "Pa", "contact.E2": "Pa", "contact.nu1": "1", "contact.nu2": "1", "contact.R1": "m",
    "contact.R2": "m", "contact.q": "1", "contact.restitution": "1", "forcing.F0": "N", "forcing.omega": "rad/s",
    "forcing.lambda": "1", "forcing.phi0": "rad", "initial.x1": "m", "initial.x2": "m", "initial.v1": "m/s",
    "initial.v2": "m/s",
}  # fmt: skip
SOFT_KCON_DEFAULT = 10.0  # analysis.soft_kcon when the scene does not set it


def key_units(branch: dict) -> str | None:
    """The unit of the branch's key: the file's, else KEY_UNITS' (by full key or by the name
    within its section); None when unknown."""
    if branch.get("units"):
        return branch["units"]
    key = branch.get("key", "")
    if key in KEY_UNITS:
        return KEY_UNITS[key]
    matches = {units for full, units in KEY_UNITS.items() if full.split(".", 1)[1] == key}
    return matches.pop() if len(matches) == 1 else None


def key_label(branch: dict) -> str:
    """The x axis label, e.g. "forcing.omega [rad/s]" ("[-]" for a dimensionless key)."""
    units = key_units(branch)
    if units is None:
        return branch["key"]
    return f"{branch['key']} [{'-' if units in ('', '1') else units}]"


def soft_kcon(scene: str) -> tuple[float, str]:
    """analysis.soft_kcon of a scene's TOML text and where it came from."""
    try:
        import tomllib  # Python 3.11

        value = tomllib.loads(scene).get("analysis", {}).get("soft_kcon")
    except ImportError:  # an older Python: the line itself
        section = re.search(r"^\[analysis\]([^\[]*)", scene, re.M)
        found = re.search(r"^\s*soft_kcon\s*=\s*([0-9.eE+-]+)", section.group(1), re.M) if section else None
        value = float(found.group(1)) if found else None
    except ValueError:
        value = None
    if isinstance(value, (int, float)) and not isinstance(value, bool) and value > 0:
        return float(value), "the scene's analysis.soft_kcon"
    if scene:
        return SOFT_KCON_DEFAULT, "analysis.soft_kcon's default"
    return SOFT_KCON_DEFAULT, "analysis.soft_kcon's default; the file does not give the scene"


# What read_branch_file needs of a branch file: its datasets and root attributes.
BRANCH_DATASETS = ("param", "stable", "x1", "x2", "v1", "v2", "k_con", "strobe_x1", "point_branch", "branch_n",
                   "branch_parent", "branch_born_at", "bifurcation_type", "bifurcation_branch", "bifurcation_param",
                   "bifurcation_x1", "bifurcation_x2", "bifurcation_v1", "bifurcation_v2")
BRANCH_ATTRIBUTES = ("key", "units", "n", "stop", "stops", "scene")


def read_branch_file(path: str) -> dict:
    """A branch file (HDF5, include/vibromap/io/branch_file.hpp) as the JSON's structure: the first
    branch's points and bifurcations at the top, the switched branches under "branches"."""
    with open_h5(path, "branch file") as f:
        for name in BRANCH_DATASETS:
            if name not in f:
                raise VibromapFileError(f"{path}: not a branch file of vibromap continue (no dataset '{name}')")
        for name in BRANCH_ATTRIBUTES:
            if name not in f.attrs:
                raise VibromapFileError(f"{path}: not a branch file of vibromap continue (no root attribute '{name}')")
        get = {name: np.asarray(read_dataset(f[name], path)) for name in BRANCH_DATASETS}
        data = {"key": _text(f.attrs["key"]), "n": int(f.attrs["n"]), "stop": _text(f.attrs["stop"]),
                "units": _text(f.attrs["units"]), "scene": _text(f.attrs["scene"])}
        stops = _text(f.attrs["stops"]).split("\n")
    owner, bif_owner, ns = get["point_branch"], get["bifurcation_branch"], get["branch_n"]

    def points(k):
        out = []
        for i in np.flatnonzero(owner == k):
            out.append({"param": float(get["param"][i]), "stable": bool(get["stable"][i]),
                        "y": [float(get[c][i]) for c in ("x1", "x2", "v1", "v2")],
                        "strobe_x1": [float(x) for x in get["strobe_x1"][i] if np.isfinite(x)],
                        "k_con": float(get["k_con"][i])})
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


# The panels (Axes.get_label), top to bottom: the bifurcations' labels, the branch, k_con along it.
PANEL_LABELS, PANEL_BRANCH, PANEL_KCON = "bifurcation-labels", "branch", "k_con"
SWITCHED_COLORS = ("#d62728", "#8c564b", "#e377c2", "#17becf", "#bcbd22")


def strobe_x1(point: dict) -> list:
    """x1 at the period starts of a point's cycle (the state's x1 alone when not given)."""
    return point.get("strobe_x1") or [point["y"][0]]


def draw_branch(ax, branch: dict, gid: str, color: str, shown: set, name: str = "branch"):
    """One branch: each period start's x1 against the key (a period-n branch draws n curves),
    stable solid and unstable dashed, its bifurcations marked at their own states."""
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


def draw_kcon(ax, branch: dict, gid: str, color: str):
    """k_con = T/T_con of each point of one branch (stable solid, unstable dashed); a point without
    impacts (k_con 0) is left out. Returns whether anything was drawn."""
    points = [p for p in branch["points"] if "k_con" in p]
    if not points:
        return False
    params = np.array([p["param"] for p in points])
    k_con = np.array([p["k_con"] if p["k_con"] > 0 else np.nan for p in points], dtype=float)
    for xs, ys, st in segments(params, k_con, [bool(p["stable"]) for p in points]):
        ax.plot(xs, ys, "-" if st else "--", color=color, linewidth=1.2, gid=f"kcon-{gid}")
    return bool(np.isfinite(k_con).any())


def bifurcation_labels(branch: dict) -> list[tuple[float, str, str]]:
    """(key value, text, kind) of each bifurcation of the first branch, by key value; one label
    for bifurcations of one kind at the same printed value."""
    labels = {}
    for b in branch.get("bifurcations", []):
        labels.setdefault((f"{b['param']:.4f}", b["type"]), float(b["param"]))
    return sorted((x, text, kind) for (text, kind), x in labels.items())


def spread(desired: list[float], widths: list[float], low: float, high: float, gap: float) -> list[float] | None:
    """Centres for labels of the given widths, in order, as close to `desired` (ascending) as they
    can be (least squares) with each at least half the two widths plus `gap` from its neighbour and
    all within [low, high]; None when they do not fit side by side. Packed, label i sits offset[i]
    after the first: the first centre each label asks for, desired - offset, is made nondecreasing
    by pooling adjacent violators (isotonic regression), then pushed inside [low, high]."""
    need = [0.0] + [0.5 * (widths[i - 1] + widths[i]) + gap for i in range(1, len(desired))]
    offset = np.cumsum(need)
    if len(desired) and offset[-1] + 0.5 * (widths[0] + widths[-1]) > high - low:
        return None
    pools: list[list[float]] = []  # [sum of the wishes, count]
    for wish in (d - o for d, o in zip(desired, offset)):
        pools.append([wish, 1])
        while len(pools) > 1 and pools[-2][0] / pools[-2][1] > pools[-1][0] / pools[-1][1]:
            total, count = pools.pop()
            pools[-1][0] += total
            pools[-1][1] += count
    centres = [total / count for total, count in pools for _ in range(int(count))]
    centres = [c + o for c, o in zip(centres, offset)]
    for i in range(len(centres)):  # inside [low, high], the order and spacing kept
        centres[i] = max(centres[i], low + 0.5 * widths[i], centres[i - 1] + need[i] if i else -np.inf)
    for i in reversed(range(len(centres))):
        nxt = centres[i + 1] - need[i + 1] if i + 1 < len(centres) else np.inf
        centres[i] = min(centres[i], high - 0.5 * widths[i], nxt)
    return centres


def place_labels(fig, strip, labels: list[tuple[float, str, str]]) -> list:
    """Writes the labels into the strip above the branch, rotated, in as few rows as keep every
    label clear of every other one (the widths measured by the figure's renderer), each joined by
    a leader to its key value at the strip's foot, where its kind's marker sits."""
    transform = strip.get_xaxis_transform()  # x in data, y in axes fraction
    texts = [strip.text(x, 0.0, text, rotation=90, ha="center", va="bottom", fontsize=7, transform=transform,
                        color=MARKERS.get(kind, ("x", "#d62728"))[1], gid="bifurcation-label")
             for x, text, kind in labels]  # fmt: skip
    fig.canvas.draw()  # lays the figure out: the axes' places and the texts' extents are final now
    fig.set_layout_engine("none")  # and stay so: the labels are placed in display coordinates
    renderer = fig.canvas.get_renderer()
    box = strip.get_window_extent(renderer)
    widths = [t.get_window_extent(renderer).width for t in texts]
    desired = [float(strip.transData.transform((x, 0))[0]) for x, _, _ in labels]
    rows = 1
    while True:
        placed = [spread(desired[r::rows], widths[r::rows], box.x0, box.x1, 3.0) for r in range(rows)]
        if all(p is not None for p in placed) or rows >= len(labels):
            break
        rows += 1
    for r in range(rows):
        for i, centre in zip(range(r, len(labels), rows), placed[r] or desired[r::rows]):
            x = strip.transData.inverted().transform((centre, box.y0))[0]
            bottom = 0.35 + 0.6 * r / rows
            texts[i].set_position((x, bottom))
            strip.plot([labels[i][0], x], [0.12, bottom - 0.03], color="#999999", linewidth=0.5, transform=transform)
    for x, _, kind in labels:
        marker, color = MARKERS.get(kind, ("x", "#d62728"))
        strip.plot([x], [0.06], marker=marker, markersize=4, color=color, transform=transform, clip_on=False)
    return texts


def title_text(branch: dict) -> str:
    switched = branch.get("branches", [])
    text = (f"branch of the period-{branch.get('n', 1)} orbit ({len(branch['points'])} points, "
            f"{len(branch.get('bifurcations', []))} bifurcations): {branch.get('stop', '')}"
            + (f"; {len(switched)} switched at period doublings" if switched else ""))  # fmt: skip
    return "\n".join(textwrap.wrap(text, 100))


def plot(branch: dict, diagram: str | None = None):
    """The figure: the bifurcation labels' strip, the branch, k_con along it; x shared."""
    fig, (strip, ax, kax) = _figure.subplots(3, 1, figsize=(9.0, 7.5), sharex=True, constrained_layout=True,
                                         gridspec_kw={"height_ratios": [0.9, 3.2, 1.6]})
    if diagram:
        name, units, values, states, key = plot_orbit_diagram.read_diagram(diagram, "x1")
        keep = states.shape[2]
        for d, color in enumerate(("#9ecae1", "#fcbba1")):
            ax.scatter(np.repeat(values, keep), states[d].reshape(-1), s=4, color=color,
                       label=f"orbit diagram, sweep {'up' if d == 0 else 'down'}")
    for panel, name in ((strip, PANEL_LABELS), (ax, PANEL_BRANCH), (kax, PANEL_KCON)):
        panel.set_label(name)
    shown = set()
    draw_branch(ax, branch, "branch", "#08306b", shown)
    drawn = draw_kcon(kax, branch, "branch", "#08306b")
    for k, switched in enumerate(branch.get("branches", []), start=1):
        n = switched.get("n", 2)
        generation = max(int(n // branch.get("n", 1)).bit_length() - 2, 0)
        color = SWITCHED_COLORS[generation % len(SWITCHED_COLORS)]
        draw_branch(ax, switched, f"branch{k}", color, shown, f"period-{n} branches")
        drawn = draw_kcon(kax, switched, f"branch{k}", color) or drawn
    ax.set_ylabel("x1 at the period start, m")
    ax.legend(loc="best", fontsize=7, ncol=2)
    threshold, source = soft_kcon(branch.get("scene", ""))
    kax.axhline(threshold, color="#2ca02c", linestyle=":", linewidth=1.2, gid="soft-threshold",
                label=f"soft threshold k_con = {threshold:g} ({source})")
    if drawn:
        kax.set_yscale("log")
    else:
        kax.text(0.5, 0.5, "no k_con in this branch (no impacts, or a file without it)", transform=kax.transAxes,
                 ha="center", va="center", fontsize=8)
    kax.set_ylabel("k_con = T/T_con")
    kax.legend(loc="best", fontsize=7)
    kax.set_xlabel(key_label(branch))
    strip.set_yticks([])
    strip.tick_params(axis="x", labelbottom=False)
    for side in ("top", "right", "left"):
        strip.spines[side].set_visible(False)
    strip.set_ylabel("bifurcations\n(first branch)", fontsize=7, rotation=0, ha="right", va="center")
    fig.suptitle(title_text(branch), fontsize=10)
    labels = bifurcation_labels(branch)
    ax.set_xlim(ax.get_xlim())  # the branch's range, fixed before the labels are placed
    place_labels(fig, strip, labels)
    return fig


@guarded_main(PROG)
def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog=PROG, description="Plot a branch of vibromap continue.")
    parser.add_argument("branch", help="branch file of vibromap continue -o (HDF5), or its --format json output")
    parser.add_argument("--diagram", help="orbit-diagram file (HDF5) of the same key to draw underneath")
    _args.add_image(parser, "BRANCH with .png")
    args = _args.finish(parser, argv, "branch")
    from . import branch

    return write_plot(PROG, lambda: branch(args.branch, args.diagram), args.output, args.dpi)


