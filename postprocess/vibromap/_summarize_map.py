"""Summarise a vibromap regime map: cells done, status and regime counts, stability, what each
cell's answer is (the map's steady: the motion from the initial state, or, for shooting, some
stable orbit, flagged as a warning), the soft cells and the Hertz-invalid cells among those with
impacts, the slowest cells, and a check that every float quantity of every computed cell is finite
(NaN is allowed only where the map says "not computed": in a quantity whose long_name says
"(NaN where not computed)", such as max_multiplier and lyapunov, and in steady_residual in a census
map). A census map adds how many cells hold 1, 2, ... attractors,
the soft fraction, the non-periodic attractors with the cells where states were seen to
leave them (transient chaos: their fractions depend on analysis.max_periods), and the largest
families of attractors across the map (regimes, soft cells, fraction range, label changes).

Usage: vibromap-post summarize_map MAP.h5 [--slowest N]
Exit status: 0 printed, 2 unreadable or damaged file, or a map of another format version (one
line "summarize_map: error: MAP.h5: ..." on stderr: its format version is not the one this
vibromap reads, its attribute checksum fails, a chunk fails its checksum, or it is truncated), 1 a
computed cell holds a non-finite value.
"""
import argparse
import sys


from ._guard import guarded_main

PROG = "summarize_map"

import numpy as np

from ._io import (FAMILY_LABEL_CHANGE, FLAG_NO, FLAG_YES, HERTZ_KEY, SOFT_KEY, VibromapFileError,
                         add_soft_cells, census_regimes, impact_cells, read_map, regime_counts)  # fmt: skip


def summary_lines(sweep, slowest: int) -> tuple[list[str], int]:
    """The summary as text lines, and the number of non-finite values in computed cells."""
    done = sweep.data["done"].astype(bool)
    lines = [f"map {sweep.path}: {int(done.sum())}/{done.size} cells done, axes "
             + ", ".join(f"{a.name} ({len(a.values)})" for a in sweep.axes.values())]
    lines.append("attributes: verified by their checksum")
    status = sweep.data["status"][done]
    lines.append("status: " + ", ".join(f"{sweep.status_meanings.get(int(c), c)} {int((status == c).sum())}"
                                         for c in sorted(set(status.tolist()))))
    labels = sweep.labels()[done]
    lines.append("regimes: " + ", ".join(f"{k} {v}" for k, v in regime_counts(labels).items()))
    stable = sweep.data["stable"][done]
    lines.append("stability: " + ", ".join(f"{sweep.stable_meanings.get(int(c), c)} {int((stable == c).sum())}"
                                           for c in sorted(set(stable.tolist()))))
    lines.extend(soft_lines(sweep, done))
    lines.extend(fragile_lines(sweep, done))
    lines.extend(refine_lines(sweep))
    wall = sweep.data["wall_s"]
    lines.append(f"wall time per cell: median {np.median(wall[done]):.3g} s, max {wall[done].max():.3g} s, "
                 f"total {wall[done].sum():.3g} s")
    order = np.argsort(np.where(done, wall, -1.0), axis=None)[::-1][:slowest]
    for flat in order:
        index = np.unravel_index(flat, wall.shape)
        where = ", ".join(f"{a.name}={a.values[i]:.3g}" for a, i in zip(sweep.axes.values(), index))
        lines.append(f"  slow: {wall[index]:.3g} s  {where}  {sweep.labels()[index]}")
    may_be_nan = sweep.not_computed_as_nan() + (["steady_residual"] if sweep.is_census else [])
    if sweep.is_census:
        lines.extend(census_lines(sweep, done))
    bad = 0
    for name, values in sweep.data.items():
        if values.dtype.kind != "f" or name in may_be_nan:
            continue
        n = int((~np.isfinite(values[done])).sum())
        if n:
            lines.append(f"NON-FINITE: {name} in {n} computed cells")
            bad += n
    lines.append("finite: every float quantity of every computed cell" if bad == 0 else f"{bad} non-finite values")
    return lines, bad


def fragile_lines(sweep, done) -> list[str]:
    """A map made with analysis.fragility: the cells whose answer a perturbation of the initial
    state changes, and their labels; nothing for a map made without."""
    fragile = sweep.fragile_cells()
    if fragile is None:
        return []
    assessed = done & (np.asarray(sweep.data["fragile"]) >= 0)
    marked = fragile & done
    labels = regime_counts(sweep.labels()[marked])
    return [f"fragile: {int(marked.sum())} of {int(assessed.sum())} cells assessed (perturbations of size "
            f"{sweep.fragility:.3g} motion scales of the initial state end on another attractor; their labels: "
            + (", ".join(f"{k} {v}" for k, v in labels.items()) or "none") + ")"]


def refine_lines(sweep) -> list[str]:
    """An adaptive map (sweep.refine > 0): its levels, the points solved per level, inherited and
    audited, and the audit's mismatches with their 95 % upper bound; nothing for a uniform map."""
    a = sweep.attrs
    if "refine_levels" not in a:
        return []
    text = lambda v: v.decode() if isinstance(v, bytes) else str(v)  # noqa: E731
    total = int(np.asarray(sweep.data["done"]).size)
    solved = int(a["refine_solved"])
    per_level = " ".join(str(int(n)) for n in np.atleast_1d(a["refine_solved_per_level"]))
    return [f"refine: {int(a['refine_levels'])} levels on {text(a['refine_on'])}: {solved} of {total} points solved "
            f"({100.0 * solved / max(total, 1):.3g} %; per level {per_level}), {int(a['refine_inherited'])} inherited",
            f"audit: {int(a['refine_mismatches'])} of {int(a['refine_audited'])} audited points differ from what they "
            f"inherited (fraction {float(a['refine_audit_fraction']):.3g}; 95 % upper bound on the mismatch rate "
            f"{float(a['refine_mismatch_bound']):.3g})"]


def soft_lines(sweep, done) -> list[str]:
    """What the cells' answers are (a warning for shooting), how many cells are soft, and how
    many of those with impacts are Hertz-invalid, each with where it comes from or why unknown."""
    lines = [f"answer: {sweep.answer_text()}"]
    if sweep.answer_warning():
        lines[0] += ('; WARNING: a cell, soft or not, may not be what the system does from rest '
                     '(analysis.steady = "follow" gives that motion)')
    info = add_soft_cells(sweep)
    soft = int((sweep.data[SOFT_KEY][done] == FLAG_YES).sum())
    lines.append(f"soft: {soft} of {int(done.sum())} cells done ({info.rule()}; {info.soft_source})")
    impacts = impact_cells(sweep.data)
    invalid = int((sweep.data[HERTZ_KEY][impacts] == FLAG_NO).sum())
    lines.append(f"{info.invalid_text()}: {invalid} of {int(impacts.sum())} cells with impacts "
                 "(from the map's hertz_valid)")
    if info.overruled:
        lines.append(f"WARNING: {info.overruled} cells the map calls soft are Hertz-invalid: not counted as soft")
    return lines


NON_PERIODIC = ("non_periodic", "chatter", "quasi_periodic", "chaotic")


def census_lines(sweep, done) -> list[str]:
    """Attractors per cell and the soft fraction of a census map."""
    count = sweep.data["attractors"][done]
    soft = sweep.data["soft_fraction"][done]
    unresolved = sweep.data["unresolved_fraction"][done]
    per = ", ".join(f"{int(a)}: {int((count == a).sum())}" for a in sorted(set(count.tolist())))
    lines = [f"census: cells with 1, 2, ... attractors: {per}"]
    if soft.size:
        lines.append(f"soft fraction: median {np.median(soft):.3g}, cells with some soft basin "
                     f"{int((soft > 0).sum())}, with soft fraction >= 0.9: {int((soft >= 0.9).sum())}")
        lines.append(f"unresolved initial states: {np.mean(unresolved):.3g} of all, at most {np.max(unresolved):.3g} in a cell")
        if "basin_entropy" in sweep.data:  # not in census maps made before vibromap computed it
            entropy = sweep.data["basin_entropy"][done]
            lines.append(f"basin entropy -sum f ln f per cell (nats): median {np.median(entropy):.3g}, "
                         f"largest {np.max(entropy):.3g}, cells above ln 2: {int((entropy > np.log(2.0)).sum())}")
        budget = sweep.data["budget_fraction"][done]
        lines.append(f"initial states followed to analysis.max_periods (no early decision): {np.mean(budget):.3g} "
                     f"of all, at most {np.max(budget):.3g} in a cell")
    # The census's attractors told by recurrence, not by a period (census.hpp).
    recurrent = [code for code, name in sweep.regime_meanings.items() if name in NON_PERIODIC]
    non_periodic = np.isin(sweep.census["regime"][done], recurrent)  # (cells, A)
    if non_periodic.any():
        line = (f"non-periodic attractors: {int(non_periodic.sum())} in {int(non_periodic.any(axis=1).sum())} cells, "
                f"basin fraction {np.nansum(np.where(non_periodic, sweep.census['fraction'][done], 0.0)) / len(non_periodic):.3g} of all")
        left = non_periodic & (sweep.census["transient"][done] == 1)
        line += f"; states seen to leave them (transient chaos) in {int(left.any(axis=1).sum())} cells"
        lines.append(line)
    lines.extend(family_lines(sweep, done))
    return lines


def family_lines(sweep, done, top: int = 5) -> list[str]:
    """The families of a finished census map (/family), the largest `top` by cells: regimes, soft
    cells, fraction range, cells where the family changes label."""
    family = sweep.census.get("family")
    if family is None or not (family[done] >= 0).any():
        return ["families: none yet (the family pass runs when the map is finished)"] if family is not None else []
    fam = family[done]
    ids, cells = np.unique(fam[fam >= 0], return_counts=True)
    lines = [f"families: {len(ids)}; the largest:"]
    for f in ids[np.argsort(-cells, kind="stable")][:top]:
        mine = fam == f
        where = np.zeros(family.shape, bool)
        where[done] = mine
        regimes = census_regimes(sweep, where)
        fraction = sweep.census["fraction"][done][mine]
        soft = int((sweep.census["soft"][done][mine] == 1).sum())
        changes = int(((sweep.census["family_flags"][done][mine] & FAMILY_LABEL_CHANGE) != 0).sum())
        lines.append(f"  family {int(f)}: {regimes}, {int(mine.sum())} cells ({soft} soft), fraction "
                     f"{np.nanmin(fraction):.3g} to {np.nanmax(fraction):.3g}, label changes in {changes} cells")
    return lines


@guarded_main(PROG)
def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.split("\n\n")[0])
    parser.add_argument("map", help="map file written by vibromap sweep")
    parser.add_argument("--slowest", type=int, default=5, help="list this many slowest cells (default 5)")
    args = parser.parse_args(argv)
    try:
        sweep = read_map(args.map)
    except VibromapFileError as exc:
        print(f"{PROG}: error: {exc}", file=sys.stderr)
        return 2
    lines, bad = summary_lines(sweep, args.slowest)
    print("\n".join(lines))
    return 1 if bad else 0


