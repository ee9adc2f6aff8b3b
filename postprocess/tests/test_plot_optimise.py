"""Tests of postprocess/plot_optimise.py: its reader of optimisation files (the layout of
include/vibromap/io/optimise_file.hpp, written here with h5py), the running best and the paths
it draws, and the three figures. The C++ writer's own files are plotted by
tests/campaigns/multistart/test_optimise_mpi.py, so reader and writer are also tested against each other.

The synthetic optimisation: free m2 (lin, [100, 310] kg) and omega2 (lin, [3.606, 5.646] rad/s),
minimising k_con, keeping (1,1):
  start 0 (bobyqa, seed 0): k_con 5, 4, 2 (a (2,1) point: infeasible, lower), 3, 3.5
                            -> best so far 5, 4, 4, 3, 3; best evaluation 3; path 0, 1, 3
  start 1 (gradient_projection, seed 1): 4.5, NaN (failed), 4.2 -> 4.5, 4.5, 4.2; best 2
  best point #0: start 0's evaluation 3, m2 = 280 kg, omega2 = 4.5 rad/s, k_con 3
The seeding map: m2 (4 points) x omega2 (3 points), (1,1) everywhere but one (2,1) cell.
"""

from __future__ import annotations

import os
import sys

import h5py
import matplotlib.colors
import matplotlib.lines
import matplotlib.pyplot
import numpy as np
import pytest

import conftest
from conftest import run
import make_map
from vibromap.plot import _optimise as plot_optimise
from stamp import stamp

SCRIPT = conftest.script("plot_optimise")
LAUNCHER = conftest.LAUNCHER
MIN_PNG_BYTES = 15_000  # each figure at 150 dpi with axes, curves and legend is well above this

REGIME_MEANINGS = "periodic chatter no_contact permanent_contact quasi_periodic chaotic non_periodic unresolved failed"
X0 = np.array([[250.0, 4.8], [260.0, 4.7], [270.0, 4.2], [280.0, 4.5], [285.0, 4.6]])
X1 = np.array([[200.0, 5.0], [205.0, 5.0], [210.0, 4.9]])
M2 = np.array([100.0, 170.0, 240.0, 310.0])
OMEGA2 = np.array([3.606, 4.626, 5.646])


def write_start(group, index, seed, algorithm, x, objective, feasible, regime_n, best):
    group.attrs["index"] = np.int64(index)
    group.attrs["seed"] = np.int64(seed)
    group.attrs["algorithm"] = algorithm
    group.attrs["stop"] = "XTOL_REACHED"
    group.attrs["best"] = np.int64(best)
    group.create_dataset("x", data=x)
    group.create_dataset("objective", data=np.asarray(objective, dtype=np.float64))
    group.create_dataset("value", data=np.asarray(objective, dtype=np.float64))
    group.create_dataset("violation", data=np.where(np.asarray(feasible) == 1, -0.03, 1.5))
    group.create_dataset("feasible", data=np.asarray(feasible, dtype=np.uint8))
    regime = group.create_dataset("regime", data=np.where(np.isnan(objective), 8, 0).astype(np.int8))
    regime.attrs["flag_values"] = np.arange(0, 9, dtype=np.int8)
    regime.attrs["flag_meanings"] = REGIME_MEANINGS
    n = np.asarray(regime_n, dtype=np.int32)
    group.create_dataset("n", data=n)
    group.create_dataset("k", data=np.where(n > 0, 1, 0).astype(np.int32))
    group.create_dataset("stable", data=np.ones(len(objective), dtype=np.int8))


def write_optimisation(path, seeds_from="map.h5", trajectory="traj.h5", integrate=None, scene="[system]\n",
                       law="hertz", restitution=1.0):
    """An optimisation file, stamped (version and attribute checksum). integrate: attributes of the
    best point's re-solve from rest replacing the defaults (z_ratio 0.012, hertz_valid 1); scene:
    the scene text attribute; law, restitution: the best point's."""
    with h5py.File(path, "w") as f:
        f.attrs["vibromap_version"] = "0.1.0"
        f.attrs["scene"] = scene
        f.attrs["variables"] = "m2 omega2"
        f.attrs["scales"] = "lin lin"
        f.attrs["quantity"] = "k_con"
        f.attrs["sense"] = "minimise"
        f.attrs["regime"] = "(1,1)"
        f.attrs["seeds_from"] = seeds_from
        f.attrs["trajectory"] = trajectory
        f.create_dataset("bounds", data=np.array([[100.0, 310.0], [3.606, 5.646]]))
        f.create_dataset("seeds", data=np.array([X0[0], X1[0]]))
        write_start(f.create_group("starts/000"), 0, 0, "bobyqa", X0, [5.0, 4.0, 2.0, 3.0, 3.5], [1, 1, 0, 1, 1],
                    [1, 1, 2, 1, 1], 3)
        write_start(f.create_group("starts/001"), 1, 1, "gradient_projection", X1, [4.5, np.nan, 4.2], [1, 0, 1],
                    [1, 0, 1], 2)
        best = f.create_group("best/00")
        best.attrs.update({"start": np.int64(0), "evaluation": np.int64(3), "objective": 3.0, "m2": 280.0,
                           "omega2": 4.5, "k2": 280.0 * 4.5**2, "E1": 2.099e11, "E2": 2.099e11, "R1": 2.0, "R2": 2.0,
                           "restitution": restitution, "law": law})
        best.create_dataset("x", data=X0[3])
        best.create_group("integrate").attrs.update({"regime": "(1,1)", "z_ratio": 0.012, "hertz_valid": np.int64(1),
                                                     **(integrate or {})})
    stamp(path, "optimisation file")


@pytest.fixture
def files(tmp_path):
    """(optimisation, map, trajectory) paths in one directory, as vibromap optimise leaves them."""
    regime = np.zeros((len(M2), len(OMEGA2)), dtype=np.int8)
    n = np.ones(regime.shape, dtype=np.int32)
    n[0, 0] = 2
    make_map.write_map(tmp_path / "map.h5", [("m2", M2, "lin"), ("omega2", OMEGA2, "lin")], regime, n,
                       np.ones(regime.shape, dtype=np.int32), quantities={"k_con": np.full(regime.shape, 4.0)})  # fmt: skip
    conftest.write_trajectory_h5(tmp_path / "traj.h5", conftest.analytic_trajectory(200, 2))
    write_optimisation(tmp_path / "opt.h5")
    return tmp_path / "opt.h5", tmp_path / "map.h5", tmp_path / "traj.h5"


# ---- the reader ---------------------------------------------------------------------------


def test_reader_returns_what_was_written(files):
    opt = plot_optimise.read_optimise(files[0])
    assert opt.variables == ["m2", "omega2"] and opt.scales == ["lin", "lin"]
    np.testing.assert_array_equal(opt.bounds, [[100.0, 310.0], [3.606, 5.646]])
    assert (opt.quantity, opt.sense, opt.regime) == ("k_con", "minimise", "(1,1)")
    assert [s.algorithm for s in opt.starts] == ["bobyqa", "gradient_projection"]
    np.testing.assert_array_equal(opt.starts[0].x, X0)
    assert opt.starts[0].labels.tolist() == ["(1,1)", "(1,1)", "(2,1)", "(1,1)", "(1,1)"]
    assert opt.starts[1].labels[1] == "failed"
    assert [s.best for s in opt.starts] == [3, 2]
    assert opt.best[0]["m2"] == 280.0 and opt.best[0]["objective"] == 3.0
    assert opt.best[0]["integrate_regime"] == "(1,1)"
    assert opt.trajectory == "traj.h5" and opt.seeds_from == "map.h5"


def test_running_best_keeps_only_feasible_improvements(files):
    opt = plot_optimise.read_optimise(files[0])
    s0, s1 = opt.starts
    np.testing.assert_array_equal(plot_optimise.running_best(s0.objective, s0.feasible, "minimise"), [5, 4, 4, 3, 3])
    np.testing.assert_array_equal(plot_optimise.running_best(s1.objective, s1.feasible, "minimise"), [4.5, 4.5, 4.2])
    np.testing.assert_array_equal(plot_optimise.running_best(s0.objective, s0.feasible, "maximise"), [5, 5, 5, 5, 5])
    first_infeasible = plot_optimise.running_best(np.array([1.0, 2.0]), np.array([False, True]), "minimise")
    assert np.isnan(first_infeasible[0]) and first_infeasible[1] == 2.0
    np.testing.assert_array_equal(plot_optimise.improving_points(s0, "minimise"), [0, 1, 3])


# ---- the figures --------------------------------------------------------------------------


def test_convergence_lines_are_the_running_best(files):
    opt = plot_optimise.read_optimise(files[0])
    fig = plot_optimise.plot_convergence(opt)
    lines = {line.get_gid(): line for line in fig.findobj(matplotlib.lines.Line2D) if line.get_gid()}
    np.testing.assert_array_equal(lines["running-best-0"].get_ydata(), [5, 4, 4, 3, 3])
    np.testing.assert_array_equal(lines["running-best-1"].get_xdata(), [1, 2, 3])
    assert fig.axes[0].get_yscale() == "linear"  # 2 .. 5: less than a decade


def test_map_figure_marks_the_best_point_and_the_paths(files):
    opt = plot_optimise.read_optimise(files[0])
    sweep = plot_optimise.read_map(files[1])
    fig, sl = plot_optimise.plot_on_map(opt, sweep, None, None, {})
    assert (sl.x.name, sl.y.name) == ("m2", "omega2")  # the free axes with the most points first
    lines = {line.get_gid(): line for line in fig.findobj(matplotlib.lines.Line2D) if line.get_gid()}
    assert lines["best-0"].get_xdata()[0] == 280.0 and lines["best-0"].get_ydata()[0] == 4.5
    np.testing.assert_array_equal(lines["path-0"].get_xdata(), X0[[0, 1, 3], 0])
    np.testing.assert_array_equal(lines["path-1"].get_ydata(), X1[[0, 2], 1])


def test_main_writes_three_figures(files, capsys):
    opt, _, _ = files
    prefix = str(opt.parent / "out")
    assert plot_optimise.main([str(opt), "-o", prefix]) == 0
    for suffix in ("_convergence.png", "_on_map.png", "_best.png"):
        assert os.path.getsize(prefix + suffix) > MIN_PNG_BYTES, suffix
    assert capsys.readouterr().out.count("plot_optimise: wrote") == 3


def test_without_a_map_the_map_figure_is_skipped(tmp_path):
    conftest.write_trajectory_h5(tmp_path / "traj.h5", conftest.analytic_trajectory(200, 2))
    write_optimisation(tmp_path / "opt.h5", seeds_from="scene")
    proc = run([*SCRIPT, str(tmp_path / "opt.h5")])
    assert proc.returncode == 0, proc.stderr
    assert "no seeding map (seeds from scene; give --map): map figure skipped" in proc.stdout
    assert (tmp_path / "opt_convergence.png").exists() and (tmp_path / "opt_best.png").exists()
    assert not (tmp_path / "opt_on_map.png").exists()


def test_bad_files_end_with_one_line_and_exit_2(tmp_path, files):
    not_opt = tmp_path / "traj.h5"  # a trajectory file is no optimisation
    for path, reason in ((tmp_path / "missing.h5", "no such file"), (not_opt, "not a vibromap optimisation file")):
        proc = run([LAUNCHER, "plot_optimise", str(path)])
        assert proc.returncode == 2
        assert proc.stderr.count("\n") == 1 and proc.stderr.startswith("plot_optimise: error: ")
        assert reason in proc.stderr
    proc = run([*SCRIPT, str(files[0]), "--x", "E9"])
    assert proc.returncode == 2
    assert "no axis 'E9' for x" in proc.stderr


@pytest.mark.parametrize("integrate, scene, expected", [
    ({"z_ratio": 0.012, "hertz_valid": np.int64(1)}, "[system]\n", "Hertz-valid: z_max/R* = 0.012 <= 0.05"),
    ({"z_ratio": 0.21, "hertz_valid": np.int64(0)}, "[system]\n", "Hertz-INVALID (not a valid answer): z_max/R* = 0.21 > 0.05"),
    ({"z_ratio": 0.21, "hertz_valid": np.int64(1)}, "[analysis]\nhertz_limit = 0.3\n", "Hertz-valid: z_max/R* = 0.21 <= 0.3"),
    ({"z_ratio": np.nan, "hertz_valid": np.int64(0)}, "[system]\n", "Hertz-INVALID (not a valid answer)"),
])  # fmt: skip
def test_best_figure_names_the_best_points_hertz_validity(files, monkeypatch, integrate, scene, expected):
    opt_path = files[0]
    write_optimisation(opt_path, integrate=integrate, scene=scene)
    titles = {}

    def keep_title(fig, path, dpi):
        titles[os.path.basename(path)] = fig._suptitle.get_text() if fig._suptitle else ""
        matplotlib.pyplot.close(fig)

    monkeypatch.setattr(plot_optimise, "save_figure", keep_title)
    assert plot_optimise.main([str(opt_path), "-o", str(opt_path.parent / "out")]) == 0
    lines = titles["out_best.png"].splitlines()
    assert lines[0].startswith("best point: regime (1,1)")
    assert lines[1] == "contact: hertz, restitution e = 1"
    assert lines[2:] == [expected]


def best_title(opt_path, monkeypatch) -> list[str]:
    titles = {}

    def keep_title(fig, path, dpi):
        titles[os.path.basename(path)] = fig._suptitle.get_text() if fig._suptitle else ""
        matplotlib.pyplot.close(fig)

    monkeypatch.setattr(plot_optimise, "save_figure", keep_title)
    assert plot_optimise.main([str(opt_path), "-o", str(opt_path.parent / "out")]) == 0
    return titles["out_best.png"].splitlines()


def test_best_figure_names_the_contact_law_and_restitution(files, monkeypatch):
    """The best point's own law and restitution (a free restitution's value), not the scene's."""
    opt_path = files[0]
    write_optimisation(opt_path, scene='[contact]\nlaw = "hunt-crossley"\nrestitution = 0.6\n', law="flores",
                       restitution=0.35)
    assert best_title(opt_path, monkeypatch)[1] == "contact: flores, restitution e = 0.35"


def test_minus_o_names_a_stem_and_drops_png(files, capsys):
    opt, _, _ = files
    assert plot_optimise.main([str(opt), "-o", str(opt.parent / "law.png")]) == 0
    for suffix in ("_convergence.png", "_on_map.png", "_best.png"):
        assert (opt.parent / f"law{suffix}").is_file(), suffix
    assert not list(opt.parent.glob("law.png*"))
    assert plot_optimise.output_stem("out/LAW.PNG", "x.h5") == "out/LAW"
    assert plot_optimise.output_stem("law", "x.h5") == "law"
    assert plot_optimise.output_stem(None, "runs/opt.h5") == "runs/opt"
    proc = run([*SCRIPT, "--help"])
    assert "-o law.png: law_convergence.png" in " ".join(proc.stdout.split())


def test_convergence_lines_of_one_algorithm_are_told_apart(tmp_path):
    """Five bobyqa starts (jobs/demo/optimise_law.toml's case, one per contact law, drew five
    same-coloured lines "start N: bobyqa, seed 0"): five colours, five labels naming each start's
    law, seed point, best value and stop."""
    laws = ["hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier"]
    path = tmp_path / "opt.h5"
    write_optimisation(path)
    with h5py.File(path, "r+") as f:
        del f["starts"], f["seeds"]
        seeds = np.array([[150.0 + 30 * i, 4.0 + 0.2 * i] for i in range(5)])
        f.create_dataset("seeds", data=seeds)
        for i in range(5):
            start = f.create_group(f"starts/{i:03d}")
            write_start(start, i, i, "bobyqa", np.tile(seeds[i], (2, 1)), [5.0 - i, 4.0 - i], [1, 1], [1, 1], 1)
            start.attrs["law"] = laws[i]
    stamp(path, "optimisation file")
    opt = plot_optimise.read_optimise(path)
    fig = plot_optimise.plot_convergence(opt)
    lines = [line for line in fig.axes[0].get_lines() if (line.get_gid() or "").startswith("running-best-")]
    labels = [line.get_label() for line in lines]
    assert len(set(labels)) == 5 and len({matplotlib.colors.to_hex(line.get_color()) for line in lines}) == 5
    assert labels[2] == "#2 bobyqa, lankarani-nikravesh, seed 2 (m2=210, omega2=4.4): best 2, XTOL_REACHED"
