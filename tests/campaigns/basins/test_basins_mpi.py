"""`vibromap basins` end to end under mpiexec, on the Table 2 point where (1,1) and (3,3) coexist.

- the file does not depend on the number of ranks (1 and 2): every dataset and attribute equal;
- labels equal brute force: 10 pixels spread over the plane, the first pixels of every
  attractor among them, followed with no early decision (basins_brute_force: a fresh
  CensusFollower with early_stop = false from the pixel's state as read back from the file)
  reach the file's attractor of the pixel (same_attractor);
- a run killed with SIGKILL (every rank) leaves the file of its last checkpoint, and --resume
  finishes it into the same file as an uninterrupted run;
- an existing file is refused without --resume or --overwrite;
- the basin entropy attributes (S_b, S_bb, the log 2 test, f(eps)) equal those recomputed here
  from /label with numpy, in the default 5 x 5 boxes and in 3 x 3 boxes after a --resume of the
  complete file with --entropy-box 3, and the JSON summary gives the same.

And `run --census` under mpiexec (the point census campaign, the same followers and codec):
- on 2 and 3 ranks every initial state's label equals the one-process census's (which equals
  brute force there: tests/core/test_census.cpp), and so do the attractors' counts, from_rest
  and their records (regime, k_con, T_con, max |mu|, to 1e-6);
- SIGUSR1 to mpiexec stops it with exit 3, one line on stderr and nothing on stdout;
- plain `run` (one point, no census) prints its summary once under mpiexec, not once per rank.

Run by ctest (tests/campaigns/campaign_tests.cmake), which sets VIBROMAP_EXE, VIBROMAP_MPIEXEC and
VIBROMAP_BASINS_BRUTE.
"""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, kill_all  # noqa: E402

BRUTE = os.environ.get("VIBROMAP_BASINS_BRUTE", "build/tests/campaigns/basins/basins_brute_force")
SCENE = "jobs/paper/table2.toml"  # m2 310, omega2 3.606, E1 1.4e10, E2 1e6: (1,1) and (3,3)
GRID = "24x24"


def basins(ranks, out, *extra, check=True):
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "basins", SCENE, "--plane", "x1,v1", "--grid", GRID, "-o", str(out),
           "--quiet", "--format", "json", *extra]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def content(path):
    with h5py.File(path, "r") as f:
        data = {name: f[name][()] for name in f if isinstance(f[name], h5py.Dataset)}
        attrs = {name: f.attrs[name] for name in f.attrs}
    return data, attrs


def assert_same_file(a, b):
    (da, aa), (db, ab) = content(a), content(b)
    assert sorted(da) == sorted(db)
    for name in da:
        np.testing.assert_array_equal(da[name], db[name], err_msg=name)
    assert sorted(aa) == sorted(ab)
    for name in aa:
        np.testing.assert_array_equal(aa[name], ab[name], err_msg=name)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The 2-rank file of the plane, and its JSON summary."""
    out = tmp_path_factory.mktemp("basins") / "two.h5"
    return out, json.loads(basins(2, out).stdout)


def test_both_attractors_and_rank_independence(reference, tmp_path):
    two, summary = reference
    regimes = [a["regime"] for a in summary["attractors"]]
    assert regimes[:2] == ["(1,1)", "(3,3)"], summary  # and one non-periodic pixel (a long chaotic transient)
    assert summary["complete"] and summary["pixels"] == 576
    assert abs(sum(a["fraction"] for a in summary["attractors"]) + (summary["unresolved"] + summary["unlisted"]) / 576
               - 1.0) < 1e-12
    one = tmp_path / "one.h5"
    basins(1, one)
    assert_same_file(one, two)
    with h5py.File(two, "r") as f:
        assert f["label"].shape == (24, 24)
        assert f["x1"].attrs["units"] == "m" and f["v1"].attrs["units"] == "m/s"
        assert int(f.attrs["complete"]) == 1 and f["done"][()].all()


def test_labels_equal_brute_force(reference):
    two, _ = reference
    with h5py.File(two, "r") as f:
        labels = f["label"][()].ravel()
        first = [int(p) for p in f["first_pixel"][()]]
        periodic = np.flatnonzero(f["periodic"][()])
    # 10 pixels: every periodic attractor's first pixel and the middle pixel of its basin, then
    # a spread of the plane (rows and columns 2 to 21) until there are 10. (A non-periodic label
    # is a transient longer than the budget: brute force with the same budget says non-periodic
    # too, but a longer one may end on an orbit, so such pixels are not compared.)
    pixels = []
    for a in periodic:
        basin = np.flatnonzero(labels == a)
        pixels += [first[a], int(basin[len(basin) // 2])]
    for j in (2, 8, 15, 21):
        for i in (2, 8, 15, 21):
            p = j * 24 + i
            if len(pixels) < 10 and p not in pixels and labels[p] in periodic:
                pixels.append(p)
    assert len(set(labels[pixels])) >= 2  # pixels of each attractor
    proc = subprocess.run([BRUTE, str(two), *map(str, pixels)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    rows = [line.split() for line in proc.stdout.splitlines()]
    assert len(rows) == 10
    agree = [r for r in rows if r[3] == "1"]
    assert len(agree) == 10, proc.stdout


def entropy_of_labels(label, box):
    """(S_b, S_bb, boxes, boundary boxes) of a (N1, N0) label array, as docs/model.md defines them:
    full box x box boxes from pixel (0, 0); outcomes every label >= -2; -3 and -4 left out."""
    n1, n0 = label.shape
    entropies, kinds = [], []
    for by in range(0, n1 - box + 1, box):
        for bx in range(0, n0 - box + 1, box):
            cell = label[by:by + box, bx:bx + box].ravel()
            cell = cell[cell >= -2]
            if cell.size == 0:
                continue
            p = np.unique(cell, return_counts=True)[1] / cell.size
            entropies.append(float(-(p * np.log(p)).sum()))
            kinds.append(len(p))
    entropies, kinds = np.array(entropies), np.array(kinds)
    boundary = kinds > 1
    s_bb = entropies[boundary].mean() if boundary.any() else 0.0
    return entropies.mean(), s_bb, len(entropies), int(boundary.sum())


def uncertain_fraction(label, eps):
    """f(eps): the share of outcome pixels with another outcome within eps pixels (square, clipped)."""
    n1, n0 = label.shape
    counted = uncertain = 0
    for j in range(n1):
        for i in range(n0):
            if label[j, i] < -2:
                continue
            counted += 1
            near = label[max(j - eps, 0):j + eps + 1, max(i - eps, 0):i + eps + 1].ravel()
            near = near[near >= -2]
            uncertain += bool((near != label[j, i]).any())
    return uncertain / counted


def assert_entropy_of_labels(path, box, summary=None):
    with h5py.File(path, "r") as f:
        label = f["label"][()].astype(int)
        attrs = dict(f.attrs)
    s_b, s_bb, boxes, boundary = entropy_of_labels(label, box)
    assert int(attrs["entropy_box"]) == box
    assert int(attrs["entropy_boxes"]) == boxes and int(attrs["entropy_boundary_boxes"]) == boundary
    assert abs(float(attrs["basin_entropy"]) - s_b) < 1e-12
    assert abs(float(attrs["boundary_basin_entropy"]) - s_bb) < 1e-12
    verdict = "no_boundary" if boundary == 0 else ("fractal" if s_bb > np.log(2.0) else "not_shown")
    assert attrs["log2_test"] == verdict
    f_eps = [uncertain_fraction(label, eps) for eps in (1, 2, 4)]  # eps <= 24 / 4
    np.testing.assert_allclose(attrs["uncertainty_fraction"], f_eps, rtol=0, atol=1e-15)
    if summary is not None:
        e = summary["entropy"]
        assert e["box"] == box and e["boxes"] == boxes and e["boundary_boxes"] == boundary
        assert abs(e["S_b"] - s_b) < 1e-12 and abs(e["S_bb"] - s_bb) < 1e-12 and e["log2_test"] == verdict
    return s_b, s_bb


def test_basin_entropy_of_the_labels(reference, tmp_path):
    two, summary = reference
    s_b, s_bb = assert_entropy_of_labels(two, 5, summary)
    assert 0.0 < s_b < s_bb  # two basins meet in the plane: some boxes, not all, on their boundary
    again = tmp_path / "again.h5"
    again.write_bytes(two.read_bytes())
    proc = basins(2, again, "--resume", "--entropy-box", "3")
    assert_entropy_of_labels(again, 3, json.loads(proc.stdout))


def wait_for_a_checkpoint(proc, out, timeout=120):
    """Waits (at most `timeout` s) until a checkpoint of the running `proc` holds some pixels of `out`."""
    done, deadline = 0, time.time() + timeout
    while proc.poll() is None and done == 0 and time.time() < deadline:
        time.sleep(0.05)
        try:
            with h5py.File(out, "r") as f:
                done = int(f.attrs["pixels_done"])
        except (OSError, KeyError):
            continue


def test_killed_run_resumes_to_the_same_file(reference, tmp_path):
    two, _ = reference
    out = tmp_path / "killed.h5"
    cmd = [MPIEXEC, "-n", "1", EXE, "basins", SCENE, "--plane", "x1,v1", "--grid", GRID, "-o", str(out), "--quiet",
           "--checkpoint", "0.2"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_a_checkpoint(proc, out)
    assert proc.poll() is None, "the run finished before it could be killed; make it longer"
    kill_all(proc.pid)
    proc.wait()
    with h5py.File(out, "r") as f:  # the file of the last checkpoint opens and is consistent
        done_mask = f["done"][()]
        assert int(f.attrs["complete"]) == 0
        assert 0 < done_mask.sum() < done_mask.size
        assert (f["label"][()][done_mask == 0] == -4).all()
        before = int(done_mask.sum())
    report = json.loads(basins(2, out, "--resume").stdout)
    assert report["pixels_resumed"] == before and report["pixels_computed"] == 576 - before
    assert_same_file(out, two)


def test_a_stopped_run_says_how_much_of_the_plane_its_fractions_cover(reference, tmp_path):
    """SIGTERM once a checkpoint holds some pixels: the summary's fractions are over the pixels
    followed so far, and the table says how many of the plane's that is (#29 item 4)."""
    _, summary = reference
    to_follow = 576 - summary["overlap"]
    assert (summary["pixels_followed"], summary["pixels_to_follow"], summary["fractions_cover"]) == \
        (to_follow, to_follow, 1.0)
    out = tmp_path / "stopped.h5"
    cmd = [EXE, "basins", SCENE, "--plane", "x1,v1", "--grid", GRID, "-o", str(out), "--quiet", "--checkpoint", "0.2"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for_a_checkpoint(proc, out)
    assert proc.poll() is None, "the run finished before it could be stopped; make it longer"
    proc.send_signal(signal.SIGTERM)
    table, err = proc.communicate(timeout=120)
    assert proc.returncode == 3, err
    with h5py.File(out, "r") as f:
        labels, done_mask = f["label"][()], f["done"][()]
    followed = int(((done_mask == 1) & (labels != -3)).sum())
    assert 0 < followed < to_follow
    lines = table.splitlines()
    assert "(stopped by SIGTERM: go on with --resume)" in lines[0]
    percent = min(100 * followed // to_follow, 99)
    overlap = ", overlap excluded" if to_follow < 576 else ""
    assert f"fractions      over {followed} of {to_follow} pixels ({percent} %){overlap}; the rest are not " \
           "computed yet" in lines
    rows = [line.split() for line in lines[lines.index("") + 2:]]  # after the blank line and the header
    assert sum(int(r[3]) for r in rows) + int(labels[(done_mask == 1) & (labels == -1)].size) + \
        int(labels[(done_mask == 1) & (labels == -2)].size) == followed
    for r in rows:
        assert abs(float(r[2]) - int(r[3]) / followed) < 1e-4  # fractions over the pixels followed


def test_existing_file_is_refused(reference, tmp_path):
    two, _ = reference
    again = basins(1, two, check=False)
    assert again.returncode == 2
    assert again.stderr.count("vibromap: error:") == 1 and "already exists" in again.stderr
    other = basins(1, two, "--resume", "--set", "system.m2=320", check=False)
    assert other.returncode == 2 and "made by another run than" in other.stderr and "system.m2" in other.stderr


def census_json(ranks, K=64):
    cmd = [EXE, "run", SCENE, "--census", "--labels", "--format", "json", "--set", f"census.initial_conditions={K}"]
    if ranks > 1:
        cmd = [MPIEXEC, "-n", str(ranks), *cmd]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


@pytest.mark.parametrize("ranks", [2, 3])
def test_point_census_on_ranks_equals_one_process(ranks):
    one, many = census_json(1), census_json(ranks)
    assert one["ranks"] == 1 and many["ranks"] == ranks
    assert len(many["labels"]) == 64
    assert many["labels"] == one["labels"]
    assert [a["regime"] for a in many["attractors"]] == ["(1,1)", "(3,3)"]
    assert many["unresolved"] == one["unresolved"] and many["unlisted"] == one["unlisted"]
    assert many["soft_fraction"] == one["soft_fraction"]
    for a, b in zip(one["attractors"], many["attractors"], strict=True):
        assert (a["regime"], a["count"], a["from_rest"], a["soft"]) == (b["regime"], b["count"], b["from_rest"], b["soft"])
        for key in ("k_con", "T_con", "max_floquet", "fraction"):
            assert b[key] == pytest.approx(a[key], rel=1e-6), key


# A point where states wander on a chaotic saddle past analysis.max_periods (Table 2's moduli,
# m2 275.2 kg, omega2 4.2607 rad/s): the follow past the budget runs on rank 0 from where the
# ranks left the states, and gives the one-process census's labels, periods and escape rate.
SADDLE = ["--set", "system.m2=275.2", "--set", "system.omega2=4.2607"]


def test_the_follow_past_the_budget_is_the_same_on_ranks():
    def census(ranks):
        cmd = [EXE, "run", SCENE, "--census", "--labels", "--format", "json", *SADDLE]
        if ranks > 1:
            cmd = [MPIEXEC, "-n", str(ranks), *cmd]
        proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, proc.stderr
        return json.loads(proc.stdout)
    one, two = census(1), census(2)
    assert one["transient_periods"] > 0, "the saddle's states are followed past the budget"
    assert two["labels"] == one["labels"]
    assert (two["periods"], two["transient_periods"], two["transient_states"]) == \
        (one["periods"], one["transient_periods"], one["transient_states"])
    saddle = [a for a in one["attractors"] if not a["periodic"]]
    assert saddle and saddle[0]["escapes"] >= 1 and saddle[0]["transient"]
    assert saddle[0]["escape_rate"] == pytest.approx(saddle[0]["escapes"] / saddle[0]["escape_exposure_periods"])
    for a, b in zip(one["attractors"], two["attractors"], strict=True):
        assert (a["regime"], a["count"], a["escapes"], a["escape_exposure_periods"]) == \
            (b["regime"], b["count"], b["escapes"], b["escape_exposure_periods"])


def test_plain_run_prints_once_under_mpiexec():
    proc = subprocess.run([MPIEXEC, "-n", "2", EXE, "run", SCENE, "--format", "json"], env=ENV, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    summary = json.loads(proc.stdout)  # one JSON object: a second rank's would make it invalid
    assert summary["regime"] == "(1,1)"


def test_point_census_stopped_by_sigusr1():
    # A demo cell on a chaotic saddle (E1 index 17, E2 index 9): 5000 states take far longer than 2 s.
    e1, e2 = (10 ** (np.log10(2e4) + i * (np.log10(2.1e11) - np.log10(2e4)) / n) for i, n in ((17, 22), (9, 21)))
    cmd = [MPIEXEC, "-n", "2", EXE, "run", "jobs/demo/e1_e2.toml", "--census", "--set", f"contact.E1={e1!r}",
           "--set", f"contact.E2={e2!r}", "--set", "census.initial_conditions=5000"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.0)
    proc.send_signal(signal.SIGUSR1)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == 3, err
    assert out == ""
    assert "run --census stopped by SIGUSR1 after" in err and "of 5000 initial states; no census printed" in err
