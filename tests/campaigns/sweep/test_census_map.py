"""Census maps end to end (issue #11): a sweep whose scene has [census] keeps, per cell, every
attractor with its basin fraction, on MPI ranks, with checkpoint and resume.

- the census map does not depend on the number of ranks (1, 2), wall_s aside;
- each cell's census equals `vibromap run --census` at that cell's point (same numbers);
- per cell, the listed fractions, the unresolved and the unlisted fractions sum to 1, and
  soft_fraction is the sum of the soft attractors' fractions, and basin_entropy is
  -sum f ln f over those shares (recomputed here), as `run --census` prints it;
- budget_fraction is the share of states `run --census` reports followed to the budget's end,
  and the report's census_budget_states their count over the map (after a resume too);
- a census sweep killed with SIGKILL resumes to the same map as an uninterrupted run;
- every listed attractor gets a family id, the same from 1 and 2 ranks and after a kill and
  resume, with the same family table (/families).
"""
import json
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, kill_all, wait_for_cells_done  # noqa: E402
from test_sweep_mpi import assert_same_map, sweep  # noqa: E402

# Table 2 (docs/model.md) over E1 x E2 where (1,1) and (3,3) coexist in places; K initial states.
CENSUS_SCENE = """
[system]
m2 = 310.0
omega2 = 3.606

[census]
initial_conditions = {k}
seed = 3
max_attractors = 4

[sweep]
E1 = {{ from = 1e9, to = 2.1e11, n = {n1}, scale = "log" }}
E2 = {{ from = 2e4, to = 1e7, n = {n2}, scale = "log" }}
store = ["k_con"]
checkpoint_interval = {checkpoint}
"""


def write_scene(tmp_path, n1, n2, checkpoint=60.0, k=8):
    path = tmp_path / "census.toml"
    path.write_text(CENSUS_SCENE.format(n1=n1, n2=n2, checkpoint=checkpoint, k=k))
    return path


def assert_same_families(a, b):
    """/family, /family_flags and the family table of maps a and b are equal, and every listed
    attractor has a family."""
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        listed = np.arange(fa["family"].shape[-1]) < fa["attractors"][()][..., None]
        assert (fa["family"][()][listed] >= 0).all() and (fa["family"][()][~listed] == -1).all()
        for name in ("family", "family_flags"):
            np.testing.assert_array_equal(fa[name][()], fb[name][()], err_msg=name)
        table_a, table_b = fa["families"], fb["families"]
        assert int(table_a.attrs["count"]) == int(table_b.attrs["count"]) == fa["family"][()].max() + 1
        assert sorted(table_a) == sorted(table_b)
        for name in table_a:
            np.testing.assert_array_equal(table_a[name][()], table_b[name][()], err_msg=name)
        assert table_a["cells"][()].sum() == listed.sum()


def test_census_map_is_rank_independent_and_equals_run_census(tmp_path):
    scene = write_scene(tmp_path, 3, 3)
    one, two = tmp_path / "one.h5", tmp_path / "two.h5"
    sweep(1, scene, one)
    report = json.loads(sweep(2, scene, two, "--format", "json").stdout)
    assert report["census_initial_conditions"] == 8
    assert abs(report["initial_conditions_per_s"] - 8 * report["cells_per_s"]) <= 1e-9 * report["initial_conditions_per_s"]
    assert_same_map(one, two)
    assert_same_families(one, two)
    assert report["families"]["count"] >= 1
    with h5py.File(two, "r") as f:
        assert int(f.attrs["census_attractors"]) == 4
        assert f["attractor_fraction"].shape == (3, 3, 4)
        count = f["attractors"][()]
        fraction = f["attractor_fraction"][()]
        soft = f["attractor_soft"][()]
        assert (count >= 1).all()
        listed = np.nansum(fraction, axis=2)
        np.testing.assert_allclose(listed + f["unresolved_fraction"][()] + f["unlisted_fraction"][()], 1.0,
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(np.where(soft == 1, fraction, 0.0).sum(axis=2), f["soft_fraction"][()],
                                   rtol=0, atol=1e-12)
        shares = np.concatenate([np.nan_to_num(fraction), f["unresolved_fraction"][()][..., None],
                                 f["unlisted_fraction"][()][..., None]], axis=2)
        entropy = -np.where(shares > 0, shares * np.log(np.where(shares > 0, shares, 1.0)), 0.0).sum(axis=2)
        np.testing.assert_allclose(f["basin_entropy"][()], entropy, rtol=0, atol=1e-12)
        # The ordinary datasets describe the attractor rest reaches.
        from_rest = f["attractor_from_rest"][()]
        for i, j in np.ndindex(3, 3):
            rest = list(from_rest[i, j]).index(1)
            assert f["n"][i, j] == f["attractor_n"][i, j, rest]
            assert f["k"][i, j] == f["attractor_k"][i, j, rest]
        # A bistable cell somewhere: more than one attractor.
        assert (count >= 2).any()
        i, j = np.argwhere(count >= 2)[0]
        e1, e2 = f["E1"][i], f["E2"][j]
        cell = {name: f[name][i, j] for name in ("attractors", "soft_fraction", "budget_fraction", "basin_entropy")}
        budget = f["budget_fraction"][()]
        assert ((budget >= 0) & (budget <= 1)).all()
        assert report["census_budget_states"] == round(8 * budget.sum())
        per = {name: f["attractor_" + name][i, j] for name in ("n", "k", "k_con", "fraction", "max_floquet", "x1")}
    run = subprocess.run([EXE, "run", str(scene), "--census", "--format", "json",
                          "--set", f"contact.E1={e1!r}", "--set", f"contact.E2={e2!r}"],
                         env=ENV, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    point = json.loads(run.stdout)
    assert point["budget_states"] / point["K"] == cell["budget_fraction"]
    assert point["basin_entropy"] == cell["basin_entropy"] > 0.0  # a cell of two attractors or more
    attractors = point["attractors"]
    assert len(attractors) == cell["attractors"]
    for a, got in enumerate(attractors):
        assert got["n"] == per["n"][a] and got["k"] == per["k"][a]
        assert got["fraction"] == per["fraction"][a]
        assert got["k_con"] == per["k_con"][a]
        if got["strobe"]:  # periodic: the first stroboscopic state; else NaN
            assert got["strobe"][0][0] == per["x1"][a]
        else:
            assert np.isnan(per["x1"][a])


def seeded_scene(tmp_path, n1, n2, checkpoint=60.0, k=4):
    path = write_scene(tmp_path, n1, n2, checkpoint=checkpoint, k=k)
    path.write_text(path.read_text().replace("max_attractors = 4", "max_attractors = 4\nseed_from_neighbour = true"))
    return path


@pytest.mark.parametrize("seeded", [False, True])
def test_killed_census_sweep_resumes_to_the_same_map(tmp_path, seeded):
    """Killed with SIGKILL and resumed, a census map (seeded from the neighbour, too) is the
    uninterrupted one (a seeded line cut by a stop, whose resumed cells compute the line's start
    again, is tests/campaigns/census's)."""
    scene = (seeded_scene if seeded else write_scene)(tmp_path, 4, 4, checkpoint=0.2, k=24)
    reference = tmp_path / "reference.h5"
    whole = json.loads(sweep(2, scene, reference, "--format", "json").stdout)

    out = tmp_path / "killed.h5"
    proc = subprocess.Popen([MPIEXEC, "-n", "2", EXE, "sweep", str(scene), "-o", str(out), "--quiet"],
                            env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_cells_done(proc, out, 3, poll=0.05)
    assert proc.poll() is None, "the census sweep finished before it could be killed; make it longer"
    kill_all(proc.pid)
    proc.wait()
    with h5py.File(out, "r") as f:
        done = f["done"][()]
        before = int(done.sum())
        assert 0 < before < done.size
        assert (f["attractors"][()][done == 0] == 0).all()
        assert np.isnan(f["attractor_fraction"][()][done == 0]).all()
    report = json.loads(sweep(2, scene, out, "--resume", "--format", "json").stdout)
    assert report["cells_resumed"] == before
    assert report["cells_computed"] == 16 - before
    assert report["census_budget_states"] == whole["census_budget_states"]
    assert_same_map(reference, out)
    assert_same_families(reference, out)
    assert report["families"] == {**whole["families"], "wall_s": report["families"]["wall_s"]}


def test_seeded_census_map_is_rank_independent_and_lists_what_the_seeds_reach(tmp_path):
    """census.seed_from_neighbour: each cell also follows the attractors of the cell before it along
    E2 (the last axis). The map is the same on 1 and 3 ranks; an attractor only seeds reach has
    count 0 and fraction 0; the unseeded map's attractors are all there (the seeds only add)."""
    scene = seeded_scene(tmp_path, 3, 4)
    one, three, plain = tmp_path / "one.h5", tmp_path / "three.h5", tmp_path / "plain.h5"
    sweep(1, scene, one)
    sweep(3, scene, three)
    assert_same_map(one, three)
    assert_same_families(one, three)
    sweep(1, write_scene(tmp_path, 3, 4, k=4), plain)
    with h5py.File(one, "r") as s, h5py.File(plain, "r") as p:
        assert "census.seed_from_neighbour = true" in s.attrs["identity"]
        assert "seed_from_neighbour" not in p.attrs["identity"]
        count_s, count_p = s["attractors"][()], p["attractors"][()]
        assert (count_s >= count_p).all()
        # The first cell of each line has no seeds: its census is the unseeded one.
        np.testing.assert_array_equal(s["attractor_fraction"][:, 0], p["attractor_fraction"][:, 0])
        # Fractions still count the K box states only, and sum to 1 with unresolved and unlisted.
        fraction = s["attractor_fraction"][()]
        np.testing.assert_allclose(np.nansum(fraction, axis=2) + s["unresolved_fraction"][()]
                                   + s["unlisted_fraction"][()], 1.0, rtol=0, atol=1e-12)
