"""Tests of the census-map reader (vibromap_h5.read_map's census), summarize_map's census lines
and postprocess/plot_census_map.py, on a map written by make_map.py with census datasets added
in the layout of include/vibromap/io/map_file.hpp, with known contents:

  E1 (log, 3 points) x R1 (lin, 2 points), attractor dimension 3; cell [i, j] lists
  1 + (i + j) % 3 attractors: a soft (1,1) from rest (fraction 1 alone, else 0.5), then a
  (3,3) and a non-periodic one sharing the rest; cell [2, 1] is not computed.
"""
import os

import h5py
import matplotlib.text
import numpy as np

import conftest
from conftest import png_size, run
import make_map
from vibromap.plot import _census_map as plot_census_map
from vibromap import _summarize_map as summarize_map
from vibromap._io import read_map

SCRIPT = conftest.script("plot_census_map")
AXES = [("E1", np.array([1e5, 1e7, 1e9]), "log"), ("R1", np.array([0.1, 1.0]), "lin")]
P, NP = make_map.REGIME["periodic"], make_map.REGIME["non_periodic"]
A = 3


def census_map(path, extra=None):
    """Writes the map; extra(path, count) adds datasets before it is sealed."""
    shape = (3, 2)
    done = np.ones(shape, dtype=bool)
    done[2, 1] = False
    regime = np.full(shape, P, dtype=np.int8)
    ones = np.ones(shape, dtype=np.int32)
    make_map.write_map(path, AXES, regime, ones, ones, done=done, stable=np.ones(shape, np.int8),
                       quantities={"k_con": np.full(shape, 8.0)})
    count = np.where(done, 1 + (np.indices(shape).sum(axis=0) % 3), 0).astype(np.int32)
    per = {name: np.full(shape + (A,), fill, dtype=dtype) for name, fill, dtype in (
        ("regime", -1, np.int8), ("stable", -1, np.int8), ("soft", -1, np.int8), ("from_rest", -1, np.int8),
        ("hertz_valid", -1, np.int8), ("transient", -1, np.int8), ("n", 0, np.int32), ("k", 0, np.int32), ("k_con", np.nan, float),
        ("fraction", np.nan, float), ("fraction_stderr", np.nan, float))}
    for name in ("T_con", "F_max", "z_ratio", "max_floquet", "x1", "x2", "v1", "v2"):  # not looked at here: NaN
        per[name] = np.full(shape + (A,), np.nan)
    soft = np.where(done, 0.0, np.nan)
    for i, j in np.ndindex(shape):
        c = int(count[i, j])
        for a in range(c):
            first = a == 0
            per["regime"][i, j, a] = P if a < 2 else NP
            per["stable"][i, j, a] = 1 if a < 2 else -1
            per["soft"][i, j, a] = 1 if first else 0
            per["from_rest"][i, j, a] = 1 if first else 0
            per["hertz_valid"][i, j, a] = 1
            per["transient"][i, j, a] = 1 if a == 2 and (i, j) == (2, 0) else 0  # one set seen to leak
            per["n"][i, j, a] = per["k"][i, j, a] = (1, 3, 0)[a]
            per["k_con"][i, j, a] = (8.0, 20.0, 30.0)[a]
            per["fraction"][i, j, a] = 1.0 if c == 1 else (0.5 if first else 0.5 / (c - 1))
            per["fraction_stderr"][i, j, a] = 0.05
        soft[i, j] = per["fraction"][i, j, 0]
    with h5py.File(path, "a") as f:
        f.attrs["census_attractors"] = np.int64(A)
        f.create_dataset("attractors", data=count)
        for name, values in (("soft_fraction", soft), ("unresolved_fraction", np.where(done, 0.0, np.nan)),
                             ("unlisted_fraction", np.where(done, 0.0, np.nan)),
                             ("budget_fraction", np.where(done, np.where(count == 3, 0.25, 0.0), np.nan))):
            f.create_dataset(name, data=values)
        for name, values in per.items():
            f.create_dataset("attractor_" + name, data=values)
    if extra is not None:
        extra(path, count)
    make_map.seal(path)
    return count, soft


def test_census_datasets_are_read_with_their_attractor_dimension(tmp_path):
    path = tmp_path / "census.h5"
    count, soft = census_map(path)
    sweep = read_map(str(path))
    assert sweep.is_census
    assert sweep.census["fraction"].shape == (3, 2, A)
    np.testing.assert_array_equal(sweep.data["attractors"], count)
    lines, bad = summarize_map.summary_lines(sweep, slowest=1)
    text = "\n".join(lines)
    assert bad == 0  # steady_residual may be NaN in a census map
    assert "cells with 1, 2, ... attractors: 1: 1, 2: 2, 3: 2" in text
    assert "with soft fraction >= 0.9: 1" in text  # the cell with one attractor
    # The two cells with 3 attractors followed a quarter of their states to the budget's end.
    assert "initial states followed to analysis.max_periods (no early decision): 0.1 of all, at most 0.25 in a cell" in text
    # Cells with 3 attractors list a non-periodic third: (1, 1) and (2, 0), each at 0.25 of the cell.
    assert ("non-periodic attractors: 2 in 2 cells, basin fraction 0.1 of all; "
            "states seen to leave them (transient chaos) in 1 cells") in text


def test_maps_and_cell_pictures(tmp_path):
    path = tmp_path / "census.h5"
    census_map(path)
    for show in ("attractors", "soft"):
        out = tmp_path / f"{show}.png"
        proc = run([*SCRIPT, str(path), "--show", show, "-o", str(out)])
        assert proc.returncode == 0, proc.stderr
        assert png_size(out) == (1350, 975)
    sweep = read_map(str(path))
    sl = plot_census_map.maps.choose_slice(sweep, None, None, {})
    fig = plot_census_map.plot_map(sweep, sl, "attractors")
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["not computed: 1 cell", "1 attractor: 1 cell", "2 attractors: 2 cells", "3 attractors: 2 cells"]
    fig = plot_census_map.plot_cell(sweep, plot_census_map.cell_index(sweep, {"E1": 1e7, "R1": 1.0}))
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert labels == ["(1,1) k_con 8 soft (from rest)", "(3,3) k_con 20", "non-periodic k_con 30"]  # top down
    fig = plot_census_map.plot_cell(sweep, plot_census_map.cell_index(sweep, {"E1": 1e9, "R1": 0.1}))
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert labels[-1] == "non-periodic k_con 30 transient"
    out = tmp_path / "cell.png"
    proc = run([*SCRIPT, str(path), "--show", "cell", "--at", "E1=1e7", "R1=1", "-o", str(out)])
    assert proc.returncode == 0, proc.stderr


def test_a_map_without_census_and_a_cell_not_computed_are_one_line_errors(tmp_path):
    plain = tmp_path / "plain.h5"
    make_map.write_map(plain, AXES, np.zeros((3, 2), np.int8), np.ones((3, 2), np.int32), np.ones((3, 2), np.int32))
    proc = run([*SCRIPT, str(plain), "-o", str(tmp_path / "x.png")])
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "not a census map" in proc.stderr
    path = tmp_path / "census.h5"
    census_map(path)
    proc = run([*SCRIPT, str(path), "--show", "cell", "--at", "E1=1e9", "R1=1", "-o", str(tmp_path / "c.png")])
    assert proc.returncode == 2 and "is not computed yet" in proc.stderr


def add_shocks_and_families(path, count):
    """Families 0, 1, 2 for attractor slots 0 (the soft (1,1)), 1, 2 of every listed attractor;
    the soft one's shock 0.5 + 0.25 (i + j), found, except cell [0, 0] where it was not looked for;
    the (3,3)'s none found; the non-periodic's not periodic (statuses as map_file.hpp's)."""
    shape = count.shape
    listed = np.arange(A) < count[..., None]
    family = np.where(listed, np.arange(A), -1).astype(np.int32)
    shock = np.full(shape + (A,), np.nan)
    status = np.where(listed, np.array([1, 2, 3], dtype=np.int8), -1).astype(np.int8)
    for i, j in np.ndindex(shape):
        if count[i, j] > 0:
            shock[i, j, 0] = 0.5 + 0.25 * (i + j)
    status[0, 0, 0], shock[0, 0, 0] = 0, np.nan
    with h5py.File(path, "a") as f:
        f.create_dataset("family", data=family)
        f.create_dataset("family_flags", data=np.zeros(shape + (A,), dtype=np.int8))
        f.create_dataset("attractor_shock", data=shock)
        f.create_dataset("attractor_shock_status", data=status)
        f.attrs["census_shock"] = np.int64(1)


def test_the_shock_map_of_a_family(tmp_path):
    """--show shock draws the soft family's shock (family 0: the most soft cells): found in the 4
    computed cells but [0, 0], where it was not searched; --family 1 draws the (3,3), whose shock
    none was found, where it is listed."""
    path = tmp_path / "census.h5"
    count, _ = census_map(path, add_shocks_and_families)
    sweep = read_map(str(path))
    chosen = plot_census_map.shock_family(sweep, None)
    assert chosen == 0
    assert plot_census_map.add_shock(sweep, chosen) == "family 0 (1,1)"
    sl = plot_census_map.maps.choose_slice(sweep, None, None, {})
    fig = plot_census_map.plot_map(sweep, sl, "shock", chosen=chosen, what="family 0 (1,1)")
    title = fig.axes[0].get_title()
    assert "shock of family 0 (1,1): found in 4 cells, 0.75 .. 1" in title
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["not there: 1 cell", "not searched (not soft): 1 cell"]
    assert plot_census_map.add_shock(sweep, 1) == "family 1 (3,3)"
    sl = plot_census_map.maps.choose_slice(sweep, None, None, {})
    fig = plot_census_map.plot_map(sweep, sl, "shock", chosen=1, what="family 1 (3,3)")
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == [f"not there: {int((count < 2).sum())} cells", f"no shock found: {int((count >= 2).sum())} cells"]
    out = tmp_path / "shock.png"
    proc = run([*SCRIPT, str(path), "--show", "shock", "-o", str(out)])
    assert proc.returncode == 0, proc.stderr
    proc = run([*SCRIPT, str(path), "--show", "shock", "--family", "7", "-o", str(out)])
    assert (proc.returncode, proc.stderr.strip()) == (2, f"plot_census_map: error: {path}: no family 7 (ids 0..2)")
