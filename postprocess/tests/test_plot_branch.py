"""Tests of postprocess/plot_branch.py on a branch in the JSON of vibromap continue: a made-up
branch over omega 1..5 (x1 = omega / 10), stable up to 3 and unstable after, with a fold at 3
(its own state x1 = -1, away from the branch, to check the marker uses it)."""
import json
import os

import matplotlib.text
import numpy as np
import pytest

import conftest
from conftest import png_size, run
from vibromap.plot import _branch as plot_branch
from stamp import stamp

SCRIPT = conftest.script("plot_branch")


def panel(fig, name):
    """The figure's panel of that name (plot_branch.PANEL_*)."""
    (ax,) = [ax for ax in fig.axes if ax.get_label() == name]
    return ax


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
    ax = panel(fig, plot_branch.PANEL_BRANCH)
    lines = {line.get_gid(): line for line in ax.get_lines()}
    np.testing.assert_allclose(lines["branch-stable"].get_xdata(), [1, 2, 3, 4])  # up to the change, included
    assert lines["branch-stable"].get_linestyle() == "-"
    np.testing.assert_allclose(lines["branch-unstable"].get_xdata(), [4, 5])
    assert lines["branch-unstable"].get_linestyle() == "--"
    fold = [c for c in ax.collections if c.get_gid() == "bifurcation-fold"][0]
    np.testing.assert_allclose(fold.get_offsets(), [[3.0, -1.0]])
    out = tmp_path / "b.png"
    proc = run([*SCRIPT, str(path), "-o", str(out)])
    assert proc.returncode == 0, proc.stderr
    assert png_size(out) == (1350, 1125)


def test_a_file_that_is_not_a_branch_is_one_line_exit_2(tmp_path):
    path = tmp_path / "x.json"
    path.write_text("[1, 2]")
    proc = run([*SCRIPT, str(path), "-o", str(tmp_path / "x.png")])
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "not a branch" in proc.stderr


def branch_file(path):
    """The same branch as branch(), in the HDF5 layout of include/vibromap/io/branch_file.hpp
    (stamped: stamp.py)."""
    import h5py

    w = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    with h5py.File(path, "w") as f:
        f.create_dataset("param", data=w)
        f.create_dataset("stable", data=(w <= 3).astype(np.int8))
        f.create_dataset("x1", data=w / 10)
        for name in ("x2", "v1", "v2"):
            f.create_dataset(name, data=np.zeros(5))
        f.create_dataset("k_con", data=10.0 + w)
        f.create_dataset("strobe_x1", data=(w / 10)[:, None])
        f.create_dataset("point_branch", data=np.zeros(5, dtype=np.int32))
        for name, value in (("branch_n", 1), ("branch_parent", -1), ("branch_born_at", -1)):
            f.create_dataset(name, data=np.array([value], dtype=np.int32))
        f.create_dataset("bifurcation_type", data=np.array([0], dtype=np.int8))
        f.create_dataset("bifurcation_branch", data=np.array([0], dtype=np.int32))
        f.create_dataset("bifurcation_param", data=np.array([3.0]))
        f.create_dataset("bifurcation_x1", data=np.array([-1.0]))
        for name in ("x2", "v1", "v2"):
            f.create_dataset("bifurcation_" + name, data=np.zeros(1))
        f.attrs["key"] = "forcing.omega"
        f.attrs["units"] = "rad/s"
        f.attrs["n"] = 1
        f.attrs["stop"] = f.attrs["stops"] = "reached the end of the interval"
        f.attrs["scene"] = "[system]\n"
        f.attrs["vibromap_version"] = "0.1.0"
    stamp(path, "branch file")


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
    ax = panel(plot_branch.plot(plot_branch.read_branch(str(path))), plot_branch.PANEL_BRANCH)
    curves = [line for line in ax.get_lines() if line.get_gid() == "branch1-stable"]
    assert len(curves) == 2
    np.testing.assert_allclose(curves[0].get_ydata(), [0.0, 0.05, 0.1])
    np.testing.assert_allclose(curves[1].get_ydata(), [0.0, -0.05, -0.1])
    assert "period-2 branches, stable" in [t.get_text() for t in ax.get_legend().get_texts()]


# ---- the figure's layout: key unit, title, labels that do not overlap, k_con -----------------

# The bifurcations Table 2's branch over omega in [3, 12] rad/s has (docs/guide-continuation.md):
# 13 of them within 3.0-3.74 rad/s and 3 within 7.575-7.586, where labels used to pile up.
TABLE2_BIFURCATIONS = (
    [("fold", w) for w in (3.7387, 3.4510, 5.1568, 4.2340, 8.2420, 7.5758)]
    + [("period-doubling", w) for w in (3.0014, 3.1259, 3.2043, 3.2635, 3.3120, 3.5850, 4.7485, 4.9378, 8.2114, 7.5829)]
    + [("neimark-sacker", w) for w in (3.2642, 3.2911, 3.6940, 3.8877, 5.3523, 6.4015)]
    + [("grazing", w) for w in (3.2634, 3.4510, 4.2421, 5.3421, 7.5855)])  # fmt: skip


def crowded_branch() -> dict:
    """A made-up branch over omega 3..12 with Table 2's bifurcations, k_con = 5 + omega^2, and a
    stop reason long enough to need wrapping."""
    w = np.linspace(3.0, 12.0, 200)
    return {"key": "forcing.omega", "n": 1, "stop": "reached the end of the interval " + "after many folds " * 12,
            "points": [{"param": x, "stable": x > 5, "y": [np.sin(x) / 10, 0, 0, 0], "k_con": 5 + x * x} for x in w],
            "bifurcations": [{"type": t, "param": x, "y": [np.sin(x) / 10, 0, 0, 0]} for t, x in TABLE2_BIFURCATIONS]}


def label_boxes(fig):
    """The label texts of the bifurcations and their boxes on the canvas (the renderer's)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    texts = [t for t in fig.findobj(matplotlib.text.Text) if t.get_gid() == "bifurcation-label"]
    return [t.get_text() for t in texts], [t.get_window_extent(renderer) for t in texts]


def overlapping(boxes) -> list[tuple[int, int]]:
    return [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes)) if boxes[i].overlaps(boxes[j])]


def assert_layout(fig, key_label: str):
    """Three panels sharing x, the key's unit on x, the title inside the figure, no two
    bifurcation labels overlapping, every label inside the figure."""
    assert [ax.get_label() for ax in fig.axes] == [plot_branch.PANEL_LABELS, plot_branch.PANEL_BRANCH, plot_branch.PANEL_KCON]
    assert panel(fig, plot_branch.PANEL_KCON).get_xlabel() == key_label
    texts, boxes = label_boxes(fig)
    assert overlapping(boxes) == []
    figure_box = fig.bbox
    title = fig._suptitle.get_window_extent(fig.canvas.get_renderer())
    for box in boxes + [title]:
        assert figure_box.x0 <= box.x0 and box.x1 <= figure_box.x1 and figure_box.y0 <= box.y0 and box.y1 <= figure_box.y1
    return texts, boxes


def test_crowded_bifurcation_labels_do_not_overlap_and_the_axis_carries_the_unit(tmp_path):
    fig = plot_branch.plot(crowded_branch())
    texts, boxes = assert_layout(fig, "forcing.omega [rad/s]")  # the unit from KEY_UNITS: JSON has none
    # One label per bifurcation: 27 (the fold and the grazing at 3.4510 are two kinds, two labels).
    assert sorted(texts) == sorted(f"{x:.4f}" for _, x in TABLE2_BIFURCATIONS)
    assert "\n" in fig._suptitle.get_text()  # wrapped
    # Unspread, the labels at 3.2634, 3.2635 and 3.2642 would sit on one another: spread, they keep
    # their order along x (so each is found next to its neighbours in value).
    centres = [0.5 * (b.x0 + b.x1) for b in boxes]
    values = [float(t) for t in texts]
    assert [values[i] for i in np.argsort(centres)] == sorted(values)
    kax = panel(fig, plot_branch.PANEL_KCON)
    (threshold,) = [line for line in kax.get_lines() if line.get_gid() == "soft-threshold"]
    assert list(threshold.get_ydata()) == [10.0, 10.0]
    (kcon,) = [line.get_ydata() for line in kax.get_lines() if line.get_gid() == "kcon-branch" and line.get_linestyle() == "-"]
    np.testing.assert_allclose(kcon[-1], 5 + 12.0**2)


def test_spread_keeps_order_spacing_and_bounds():
    assert plot_branch.spread([0, 1, 2, 50, 50.5, 51], [4] * 6, 0, 100, 1) == [2.0, 7.0, 12.0, 45.5, 50.5, 55.5]
    assert plot_branch.spread([99, 99, 99], [4] * 3, 0, 100, 1) == [88.0, 93.0, 98.0]
    assert plot_branch.spread([50] * 30, [4] * 30, 0, 100, 1) is None  # 30 x 5 > 100: rows of them


def test_units_of_json_keys_and_the_soft_threshold_of_the_scene():
    assert plot_branch.key_label({"key": "omega"}) == "omega [rad/s]"
    assert plot_branch.key_label({"key": "system.xi1"}) == "system.xi1 [-]"
    assert plot_branch.key_label({"key": "contact.E1", "units": "Pa"}) == "contact.E1 [Pa]"
    assert plot_branch.key_label({"key": "no.such"}) == "no.such"
    assert plot_branch.soft_kcon("[analysis]\nsoft_kcon = 25.0\n")[0] == 25.0
    assert plot_branch.soft_kcon("[system]\nm1 = 1000.0\n") == (10.0, "analysis.soft_kcon's default")


@pytest.mark.skipif("VIBROMAP_EXE" not in os.environ, reason="no vibromap to run (ctest sets VIBROMAP_EXE)")
def test_the_branch_of_table2_from_vibromap_continue(tmp_path):
    """`vibromap continue jobs/paper/table2.toml --param forcing.omega --from 3 --to 12 -o b.h5`
    (with --pd-depth 0: the first branch, whose labels are drawn, is the same): the unit from the
    file, its 27 bifurcations labelled, none over another, k_con along it under the threshold of
    the scene (analysis.soft_kcon, 10 in Table 2's scene, which does not set it)."""
    out = tmp_path / "b.h5"
    scene = os.path.join(conftest.POSTPROCESS_DIR, "..", "jobs", "paper", "table2.toml")
    proc = run([os.environ["VIBROMAP_EXE"], "continue", scene, "--param", "forcing.omega", "--from", "3", "--to", "12",
                "--pd-depth", "0", "-o", str(out)])
    assert proc.returncode == 0, proc.stderr
    data = plot_branch.read_branch(str(out))
    assert data["units"] == "rad/s" and len(data["bifurcations"]) == 27
    fig = plot_branch.plot(data)
    texts, _ = assert_layout(fig, "forcing.omega [rad/s]")
    assert len(texts) == 27 and "8.2420" in texts and "7.5758" in texts
    kax = panel(fig, plot_branch.PANEL_KCON)
    (threshold,) = [line for line in kax.get_lines() if line.get_gid() == "soft-threshold"]
    assert list(threshold.get_ydata()) == [10.0, 10.0] and "analysis.soft_kcon's default" in threshold.get_label()
    drawn = np.concatenate([line.get_ydata() for line in kax.get_lines() if line.get_gid() == "kcon-branch"])
    assert np.nanmin(drawn) > 0 and np.isfinite(drawn).sum() > 3000
    png = tmp_path / "b.png"
    proc = run([*SCRIPT, str(out), "-o", str(png)])
    assert proc.returncode == 0, proc.stderr
    assert png_size(png) == (1350, 1125)
