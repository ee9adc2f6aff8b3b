"""Tests of postprocess/plot_branch.py on a branch in the JSON of vibromap continue: a made-up
branch over omega 1..5 (x1 = omega / 10), stable up to 3 and unstable after, with a fold at 3
(its own state x1 = -1, away from the branch, to check the marker uses it)."""
import json
import os

import numpy as np

import conftest
from conftest import png_size, run
import plot_branch

SCRIPT = os.path.join(conftest.POSTPROCESS_DIR, "plot_branch.py")


def branch(path):
    points = [{"param": w, "stable": w <= 3, "y": [w / 10, 0.05, 0, 0], "multipliers": [[0.5, 0]]}
              for w in (1.0, 2.0, 3.0, 4.0, 5.0)]
    data = {"key": "forcing.omega", "n": 1, "stop": "reached the end of the interval", "points": points,
            "bifurcations": [{"type": "fold", "param": 3.0, "multipliers": [[1, 0]], "y": [-1.0, 0, 0, 0]}]}
    path.write_text(json.dumps(data))


def test_stable_solid_unstable_dashed_and_the_bifurcation_at_its_state(tmp_path):
    path = tmp_path / "b.json"
    branch(path)
    fig = plot_branch.plot(plot_branch.read_branch(str(path)))
    ax = fig.axes[0]
    lines = {line.get_gid(): line for line in ax.get_lines()}
    np.testing.assert_allclose(lines["branch-stable"].get_xdata(), [1, 2, 3, 4])  # up to the change, included
    assert lines["branch-stable"].get_linestyle() == "-"
    np.testing.assert_allclose(lines["branch-unstable"].get_xdata(), [4, 5])
    assert lines["branch-unstable"].get_linestyle() == "--"
    fold = [c for c in ax.collections if c.get_gid() == "bifurcation-fold"][0]
    np.testing.assert_allclose(fold.get_offsets(), [[3.0, -1.0]])
    out = tmp_path / "b.png"
    proc = run([SCRIPT, str(path), "-o", str(out)])
    assert proc.returncode == 0, proc.stderr
    assert png_size(out) == (1350, 825)


def test_a_file_that_is_not_a_branch_is_one_line_exit_2(tmp_path):
    path = tmp_path / "x.json"
    path.write_text("[1, 2]")
    proc = run([SCRIPT, str(path), "-o", str(tmp_path / "x.png")])
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "not a branch" in proc.stderr


def branch_file(path):
    """The same branch as branch(), in the HDF5 layout of include/vibromap/io/branch_file.hpp."""
    import h5py

    w = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    with h5py.File(path, "w") as f:
        f.create_dataset("param", data=w)
        f.create_dataset("stable", data=(w <= 3).astype(np.int8))
        f.create_dataset("x1", data=w / 10)
        for name in ("x2", "v1", "v2"):
            f.create_dataset(name, data=np.zeros(5))
        f.create_dataset("bifurcation_type", data=np.array([0], dtype=np.int8))
        f.create_dataset("bifurcation_param", data=np.array([3.0]))
        f.create_dataset("bifurcation_x1", data=np.array([-1.0]))
        for name in ("x2", "v1", "v2"):
            f.create_dataset("bifurcation_" + name, data=np.zeros(1))
        f.attrs["key"] = "forcing.omega"
        f.attrs["n"] = 1
        f.attrs["stop"] = "reached the end of the interval"


def test_the_hdf5_branch_file_reads_as_the_json(tmp_path):
    json_path, h5_path = tmp_path / "b.json", tmp_path / "b.h5"
    branch(json_path)
    branch_file(h5_path)
    a, b = plot_branch.read_branch(str(json_path)), plot_branch.read_branch(str(h5_path))
    assert b["key"] == a["key"] and b["stop"] == a["stop"]
    assert [(p["param"], p["stable"], p["y"][0]) for p in b["points"]] == [
        (p["param"], p["stable"], p["y"][0]) for p in a["points"]]
    assert b["bifurcations"] == [{"type": "fold", "param": 3.0, "y": [-1.0, 0.0, 0.0, 0.0]}]


def test_a_switched_period_two_branch_draws_one_curve_per_period_start(tmp_path):
    """A period-2 branch switched onto at the fold's place: its two stroboscopic x1 per point are
    two curves (x1 = +-(3 - omega) / 10 over omega 2..3), stable solid, in the branch's own gid."""
    path = tmp_path / "b.json"
    branch(path)
    data = json.loads(path.read_text())
    data["branches"] = [{"n": 2, "parent": 0, "born_at": 0, "stop": "rejoined the period-1 orbit",
                         "points": [{"param": w, "stable": True, "y": [(3 - w) / 10, 0.05, 0, 0],
                                     "strobe_x1": [(3 - w) / 10, -(3 - w) / 10]} for w in (3.0, 2.5, 2.0)],
                         "bifurcations": []}]
    path.write_text(json.dumps(data))
    ax = plot_branch.plot(plot_branch.read_branch(str(path))).axes[0]
    curves = [line for line in ax.get_lines() if line.get_gid() == "branch1-stable"]
    assert len(curves) == 2
    np.testing.assert_allclose(curves[0].get_ydata(), [0.0, 0.05, 0.1])
    np.testing.assert_allclose(curves[1].get_ydata(), [0.0, -0.05, -0.1])
    assert "period-2 branches, stable" in [t.get_text() for t in ax.get_legend().get_texts()]
