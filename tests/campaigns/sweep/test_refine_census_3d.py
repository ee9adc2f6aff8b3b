"""Adaptive maps (sweep.refine, issue #30) end to end beyond test_refine_map.py's plane:

- a census map (test_census_map.py's scene, K = 6) refined on the census's attractor count;
- a map over three axes (4 x 3 x 2 coarse points, L = 1, refined on n and k);
each the same map (every dataset but wall_s, and the refine attributes) on 1 and 2 ranks and
after a kill -9 in level 1 and a --resume; and the report and progress lines count points: the
final line solved / audited / inherited (from the map's own /computed), the points solved now
(the fill solves none), each phase's progress line (coarse, level 1/1, audit) its own points,
with the points solved and inferred so far.

Run by ctest (tests/campaigns/campaign_tests.cmake), which sets VIBROMAP_EXE and VIBROMAP_MPIEXEC.
"""
import json
import os
import re
import sys

import h5py
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import EXE, MPIEXEC, SLOW_SYSTEM  # noqa: E402
from test_census_map import CENSUS_SCENE  # noqa: E402
from test_refine_map import assert_same_map, kill_in_level, sweep  # noqa: E402

# Census: 5 x 4 coarse points over E1 x E2 where a point has 1, 2 or 3 attractors: 9 x 7 fine.
# The counts change back and forth along E2 there, so speckle would solve every cell whole: the
# corners alone decide here, so that points are inherited (census datasets copied by the fill).
CENSUS_REFINED = CENSUS_SCENE + 'refine = 1\nrefine_on = ["attractors"]\nrefine_audit = 0.25\nrefine_speckle = false\n'
# Three axes, Table 2's system from rest, brute force (slow enough to be killed mid-run): n = 2
# at the lowest E2 and F0 only, so some blocks are refined and others inherit: 7 x 5 x 3 fine.
THREE_AXES = SLOW_SYSTEM + """
[sweep]
E1 = {{ from = 1e9, to = 2.1e11, n = 4, scale = "log" }}
E2 = {{ from = 2e4, to = 1e7, n = 3, scale = "log" }}
F0 = {{ from = 300.0, to = 700.0, n = 2 }}
store = ["k_con"]
refine = 1
refine_on = ["n", "k"]
refine_audit = 0.25
checkpoint_interval = {checkpoint}
"""
# name: (scene text for a checkpoint interval, fine shape, coarse points, the dataset refined on)
CASES = {
    "census": (lambda c: CENSUS_REFINED.format(n1=5, n2=4, checkpoint=c, k=6), (9, 7), 20, "attractors"),
    "three_axes": (lambda c: THREE_AXES.format(checkpoint=c), (7, 5, 3), 24, "n"),
}


def write_scene(tmp_path, case, checkpoint=60.0):
    path = tmp_path / f"{case}.toml"
    path.write_text(CASES[case][0](checkpoint))
    return path


def refined(*args, **kwargs):
    return sweep(*args, refine=[], **kwargs)  # the refine keys are the scene's


def figures(path):
    with h5py.File(path, "r") as f:
        computed = f["computed"][()]
        per_level = f.attrs["refine_solved_per_level"]
        return computed, [int(n) for n in per_level], {name: int(f.attrs["refine_" + name])
                                                       for name in ("solved", "audited", "inherited")}  # fmt: skip


def check_report_and_progress(proc, path, total, coarse):
    """The table's points line and rate, and each phase's last progress line, against the map."""
    computed, per_level, fig = figures(path)
    solved, audited, inherited = fig["solved"], fig["audited"], fig["inherited"]
    assert (solved, audited, inherited) == ((computed == 1).sum(), (computed == 2).sum(), (computed == 0).sum())
    assert solved + audited + inherited == total and 0 < inherited and 0 < audited
    assert (f"points         {total} ({solved} solved, {audited} audited, {inherited} inherited; "
            f"0 from the resumed map, {solved + audited} solved now)\n") in proc.stdout
    assert re.search(r"\nwall time      [0-9.e+-]+ s, [0-9.e+-]+ points solved/s\n", proc.stdout), proc.stdout
    assert "\ncells " not in proc.stdout
    last = {}
    for line in proc.stderr.splitlines():
        if line.startswith("sweep "):
            last[line.split(":")[0]] = line
    assert sorted(last) == ["sweep audit", "sweep coarse", "sweep level 1/1"], proc.stderr
    assert last["sweep coarse"].startswith(f"sweep coarse: {coarse}/{coarse} points (100.0%), ")
    assert f"| {coarse} solved, 0 inferred of {total} points |" in last["sweep coarse"]
    level = per_level[1]
    assert last["sweep level 1/1"].startswith(f"sweep level 1/1: {level}/{level} points (100.0%), ")
    # After the last level every point not solved is known to be inherited.
    assert f"| {solved} solved, {total - solved} inferred of {total} points |" in last["sweep level 1/1"]
    assert last["sweep audit"].startswith(f"sweep audit: {audited}/{audited} points (100.0%), ")
    assert f"| {solved + audited} solved, {inherited} inferred of {total} points |" in last["sweep audit"]


@pytest.mark.parametrize("case", sorted(CASES))
def test_adaptive_map_is_the_same_on_1_and_2_ranks(tmp_path, case):
    scene = write_scene(tmp_path, case)
    _, shape, coarse, quantity = CASES[case]
    one, two = tmp_path / "one.h5", tmp_path / "two.h5"
    proc = refined(1, scene, one, quiet=False)
    check_report_and_progress(proc, one, int(np.prod(shape)), coarse)
    report = json.loads(refined(2, scene, two, "--format", "json").stdout)
    assert report["points_solved_now"] == report["refine_solved"] + report["refine_audited"]
    assert report["cells_total"] == int(np.prod(shape)) and report["complete"]
    assert_same_map(one, two)
    with h5py.File(one, "r") as f:
        assert f["done"].shape == shape and f["done"][()].all()
        assert f.attrs["refine_on"] == ("attractors" if case == "census" else "n k")
        values, computed = f[quantity][()], f["computed"][()]
        coarse_points = computed[tuple(slice(None, None, 2) for _ in shape)]
        assert coarse_points.size == coarse and (coarse_points == 1).all()
        # The quantity refined on varies over the map (else nothing would be refined).
        assert len(np.unique(values)) > 1
        if case == "census":
            assert (f["attractors"][()] >= 1).all() and f["attractor_fraction"].shape == shape + (4,)


@pytest.mark.parametrize("case", sorted(CASES))
def test_killed_adaptive_map_resumes_to_the_same_map(tmp_path, case):
    scene = write_scene(tmp_path, case, checkpoint=0.1)
    _, shape, coarse, _ = CASES[case]
    reference = tmp_path / "reference.h5"
    refined(2, scene, reference)

    out = tmp_path / "killed.h5"
    cmd = [MPIEXEC, "-n", "2", EXE, "sweep", str(scene), "-o", str(out), "--quiet"]
    done = kill_in_level(cmd, out, coarse + 4, poll=0.05)
    with h5py.File(out, "r") as f:
        assert 0 < done.sum() < done.size
        assert (f["computed"][()][done == 1] >= 1).all()  # killed before the fill: every point done was solved

    report = json.loads(refined(2, scene, out, "--resume", "--format", "json").stdout)
    assert report["cells_resumed"] == int(done.sum()) and report["complete"]
    assert report["points_solved_now"] == report["refine_solved"] + report["refine_audited"] - int(done.sum())
    assert_same_map(reference, out)
