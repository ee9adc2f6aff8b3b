"""Adaptive maps (sweep.refine, issue #30) end to end under mpiexec.

- the map is the fine grid ((n - 1) 2^L + 1 points per axis, coarse points among them), every
  point done, computed/level consistent with the refine attributes;
- it does not depend on the number of ranks (1, 2, 3): every dataset but wall_s identical, and
  the refine attributes too;
- a run killed with SIGKILL in the middle of its phases and resumed gives the same map;
- a uniform map (refine = 0) reports cells as it always did.

Run by ctest (tests/sweep_tests.cmake), which sets VIBROMAP_EXE and VIBROMAP_MPIEXEC.
"""
import json
import re
import os
import subprocess
import sys

import pathlib

import h5py
import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, kill_all, slow_scene, wait_for_cells_done  # noqa: E402

REFINE = ["--set", "sweep.refine=2", "--set", "sweep.refine_audit=0.25"]
FIGURES = ["refine_levels", "refine_on", "refine_audit_fraction", "refine_solved_per_level", "refine_solved",
           "refine_inherited", "refine_audited", "refine_mismatches", "refine_mismatch_bound"]


def write_scene(tmp_path, n1=4, n2=3, checkpoint=60.0):
    path = tmp_path / "scene.toml"
    path.write_text(slow_scene(n1, n2, checkpoint))
    return path


def sweep(ranks, scene, out, *extra, refine=REFINE, quiet=True):
    """`vibromap sweep` on `ranks` ranks with the refine keys `refine` (none: the scene's own)."""
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "sweep", str(scene), "-o", str(out), *(["--quiet"] if quiet else []),
           *refine, *extra]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return proc


def kill_in_level(cmd, out, cells, poll=0.1):
    """Starts the sweep `cmd` writing `out`, kills it (kill -9, every rank) once its map counts
    `cells` done (past the coarse points: in level 1 or later) and returns /done as it was left."""
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_cells_done(proc, out, cells, poll=poll)
    assert proc.poll() is None, "the sweep finished before it could be killed; make it longer"
    kill_all(proc.pid)
    proc.wait()
    with h5py.File(out, "r") as f:
        assert int(f.attrs["complete"]) == 0
        return f["done"][()]


def contents(path):
    with h5py.File(path, "r") as f:
        data = {name: f[name][()] for name in f if isinstance(f[name], h5py.Dataset) and name != "wall_s"}
        attrs = {name: f.attrs[name] for name in FIGURES}
    return data, attrs


def assert_same_map(a, b):
    (da, aa), (db, ab) = contents(a), contents(b)
    assert sorted(da) == sorted(db)
    for name in da:
        np.testing.assert_array_equal(da[name], db[name], err_msg=name)
    for name in FIGURES:
        np.testing.assert_array_equal(aa[name], ab[name], err_msg=name)


def test_adaptive_map_is_the_fine_grid_and_the_same_on_1_2_3_ranks(tmp_path):
    scene = write_scene(tmp_path)
    maps = []
    for ranks in (1, 2, 3):
        out = tmp_path / f"map{ranks}.h5"
        report = json.loads(sweep(ranks, scene, out, "--format", "json").stdout)
        maps.append(out)
    with h5py.File(maps[0], "r") as f:
        assert f["regime"].shape == (13, 9)  # (4 - 1) 4 + 1, (3 - 1) 4 + 1
        assert f["done"][()].all()
        computed, level = f["computed"][()], f["level"][()]
        assert set(np.unique(computed)) <= {0, 1, 2}
        assert (computed[::4, ::4] == 1).all() and (level[::4, ::4] == 0).all()  # the coarse points
        e1 = f["E1"][()]
        assert e1[0] == 2e4 and e1[-1] == 2.1e11
        np.testing.assert_allclose(e1[::4], np.geomspace(2e4, 2.1e11, 4), rtol=1e-14)
        np.testing.assert_allclose(e1[2], np.sqrt(e1[0] * e1[4]), rtol=1e-14)  # log: midpoints geometric
        assert int(f.attrs["refine_levels"]) == 2
        assert f.attrs["refine_on"] == "regime n k soft"
        assert int(f.attrs["refine_solved"]) == (computed == 1).sum()
        assert int(f.attrs["refine_inherited"]) == (computed == 0).sum()
        assert int(f.attrs["refine_audited"]) == (computed == 2).sum()
        per_level = f.attrs["refine_solved_per_level"]
        assert per_level[0] == 12 and per_level.sum() == (computed == 1).sum()
        for l in (1, 2):
            assert per_level[l] == ((computed == 1) & (level == l)).sum()
    assert report["refine_solved"] == int(per_level.sum())
    assert report["cells_total"] == 117 and report["complete"]
    for other in maps[1:]:
        assert_same_map(maps[0], other)
    summary = subprocess.run([str(REPO / "postprocess" / "vibromap-post"), "summarize_map", str(maps[0])],
                             capture_output=True, text=True, timeout=120)
    assert summary.returncode == 0, summary.stderr
    solved = int(per_level.sum())
    assert (f"refine: 2 levels on regime n k soft: {solved} of 117 points solved "
            f"({100.0 * solved / 117:.3g} %; per level {' '.join(str(int(n)) for n in per_level)})") in summary.stdout
    assert f"audit: {report['refine_mismatches']} of {report['refine_audited']} audited points differ" in summary.stdout


def test_killed_adaptive_sweep_resumes_to_the_same_map(tmp_path):
    scene = write_scene(tmp_path, n1=6, n2=4, checkpoint=0.3)
    reference = tmp_path / "reference.h5"
    sweep(2, scene, reference)
    with h5py.File(reference, "r") as f:
        solved = int(f.attrs["refine_solved"])

    out = tmp_path / "killed.h5"
    cmd = [MPIEXEC, "-n", "2", EXE, "sweep", str(scene), "-o", str(out), "--quiet", *REFINE]
    done = kill_in_level(cmd, out, 30)  # past the 24 coarse points
    assert 0 < done.sum() < min(solved, done.size)

    report = json.loads(sweep(2, scene, out, "--resume", "--format", "json").stdout)
    assert report["cells_resumed"] == int(done.sum()) and report["complete"]
    assert_same_map(reference, out)


def test_uniform_map_report_counts_cells_as_before(tmp_path):
    # refine = 0: the report's lines are a uniform map's, cells computed and cells/s (an adaptive
    # map's points line is checked by test_refine_census_3d.py).
    scene = write_scene(tmp_path, n1=2, n2=2)
    proc = sweep(1, scene, tmp_path / "uniform.h5", refine=[])
    assert "cells          4 (0 from the resumed map, 4 computed now)\n" in proc.stdout
    assert re.search(r"\nwall time      [0-9.e+-]+ s, [0-9.e+-]+ cells/s\n", proc.stdout), proc.stdout
    assert "\npoints " not in proc.stdout and "\nrefine " not in proc.stdout
