"""`vibromap basins` end to end under mpiexec, on the Table 2 point where (1,1) and (3,3) coexist.

- the file does not depend on the number of ranks (1 and 2): every dataset and attribute equal;
- labels equal brute force: 10 pixels spread over the plane, the first pixels of every
  attractor among them, followed with no early decision (basins_brute_force: a fresh
  CensusFollower with early_stop = false from the pixel's state as read back from the file)
  reach the file's attractor of the pixel (same_attractor);
- a run killed with SIGKILL (every rank) leaves the file of its last checkpoint, and --resume
  finishes it into the same file as an uninterrupted run;
- an existing file is refused without --resume or --overwrite.

Run by ctest (tests/campaigns/campaign_tests.cmake), which sets VIBROMAP_EXE, VIBROMAP_MPIEXEC and
VIBROMAP_BASINS_BRUTE.
"""
import json
import os
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


def test_killed_run_resumes_to_the_same_file(reference, tmp_path):
    two, _ = reference
    out = tmp_path / "killed.h5"
    cmd = [MPIEXEC, "-n", "1", EXE, "basins", SCENE, "--plane", "x1,v1", "--grid", GRID, "-o", str(out), "--quiet",
           "--checkpoint", "0.2"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    done, deadline = 0, time.time() + 120
    while proc.poll() is None and done == 0 and time.time() < deadline:
        time.sleep(0.05)
        try:
            with h5py.File(out, "r") as f:
                done = int(f.attrs["pixels_done"])
        except (OSError, KeyError):
            continue
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


def test_existing_file_is_refused(reference, tmp_path):
    two, _ = reference
    again = basins(1, two, check=False)
    assert again.returncode == 2
    assert again.stderr.count("vibromap: error:") == 1 and "already exists" in again.stderr
    other = basins(1, two, "--resume", "--set", "system.m2=320", check=False)
    assert other.returncode == 2 and "another run" in other.stderr and "system.m2" in other.stderr
