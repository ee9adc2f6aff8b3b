"""Tests of postprocess/plot_trajectory.py, its reader (vibromap_h5.read_trajectory) and the
postprocess/vibromap-post launcher. Files are made with h5py from analytic formulas (conftest.py);
when VIBROMAP_SAMPLE_TRAJECTORY names a file written by the C++ writer (ctest sets it), that
file is checked against the same formulas, so writer and reader are tested against each other."""

from __future__ import annotations

import os
import sys

import h5py
import matplotlib.image
import numpy as np
import pytest

import conftest
from conftest import run, png_size, pixels_near
from vibromap.plot import _trajectory as plot_trajectory
from vibromap import _io as vibromap_h5
from stamp import stamp

SCRIPT = conftest.script("plot_trajectory")
LAUNCHER = conftest.LAUNCHER
MIN_PNG_BYTES = 20_000  # a two-panel figure with four curves at 1200 x 900 px is well above this


# ---- the reader ---------------------------------------------------------------------------


def test_reader_returns_the_arrays_written(trajectory_file):
    path, columns = trajectory_file
    traj = vibromap_h5.read_trajectory(path)
    for name, values in columns.items():
        np.testing.assert_array_equal(getattr(traj, name), values, err_msg=name)
    assert traj.units == conftest.UNITS
    assert traj.T == conftest.T
    assert traj.regime == "(1,1)" and (traj.n, traj.k) == (1, 1)
    assert traj.T_con == conftest.T_CON
    assert traj.k_con == pytest.approx(1113.3, rel=1e-3)  # the paper's Table 1 value, by construction
    assert traj.scene == "[system]\nm1 = 1000.0\n"
    assert traj.phase[-1] == pytest.approx(3.0, rel=1e-15)
    # Spot values against the formulas themselves: quarter period and the contact-force peak.
    assert traj.x1[50] == pytest.approx(conftest.A1, abs=1e-16)
    assert traj.Fc.max() == pytest.approx(conftest.FC_MAX, rel=1e-12)


def test_reader_rejects_a_file_without_trajectory_datasets(tmp_path):
    path = tmp_path / "other.h5"
    with h5py.File(path, "w") as f:
        f.create_dataset("t", data=np.zeros(3))
    stamp(path, "trajectory file")
    with pytest.raises(vibromap_h5.VibromapFileError, match="no dataset 'x1'"):
        vibromap_h5.read_trajectory(path)


def test_reader_rejects_datasets_of_unequal_length(tmp_path):
    columns = conftest.analytic_trajectory(10, 1)
    columns["Fc"] = columns["Fc"][:-1]
    path = tmp_path / "ragged.h5"
    conftest.write_trajectory_h5(path, columns)
    with pytest.raises(vibromap_h5.VibromapFileError, match="differ in length"):
        vibromap_h5.read_trajectory(path)


@pytest.mark.skipif("VIBROMAP_SAMPLE_TRAJECTORY" not in os.environ, reason="no file from the C++ writer (run via ctest)")
def test_reader_reads_the_cpp_writers_file():
    """tests/io/test_trajectory_file.cpp writes the analytic motion of conftest with 64 samples per
    period over 2 periods; libm and numpy may differ in the last bit of sin/cos."""
    traj = vibromap_h5.read_trajectory(os.environ["VIBROMAP_SAMPLE_TRAJECTORY"])
    expected = conftest.analytic_trajectory(64, 2)
    np.testing.assert_array_equal(traj.t, expected["t"])  # same IEEE operations: exact
    for name in ("x1", "x2", "v1", "v2", "Fc", "F"):
        np.testing.assert_allclose(getattr(traj, name), expected[name], rtol=1e-14, atol=1e-14 * np.abs(expected[name]).max(), err_msg=name)
    assert traj.units == conftest.UNITS
    assert traj.T == conftest.T
    assert (traj.regime, traj.n, traj.k) == ("(1,1)", 1, 1)
    assert traj.T_con == conftest.T_CON and traj.k_con == conftest.T / conftest.T_CON
    assert "[system]" in traj.scene
    assert isinstance(traj.vibromap_version, str) and traj.vibromap_version


# ---- the script ---------------------------------------------------------------------------


def test_plot_writes_a_png_of_the_expected_size_and_content(trajectory_file, tmp_path):
    path, _ = trajectory_file
    out = tmp_path / "fig.png"
    result = run([*SCRIPT, str(path), "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    assert out.is_file()
    assert png_size(out) == (1200, 900)  # 8 x 6 in at 150 dpi
    assert out.stat().st_size > MIN_PNG_BYTES
    image = matplotlib.image.imread(out)
    assert pixels_near(image, plot_trajectory.COLOR_FC, tol=0.08) > 500  # the contact-force curve is drawn
    assert pixels_near(image, plot_trajectory.COLOR_X2, tol=0.08) > 500  # the attached body's curve is drawn


def test_default_output_is_next_to_the_input(trajectory_file):
    path, _ = trajectory_file
    result = run([*SCRIPT, str(path), "--dpi", "50"])
    assert result.returncode == 0, result.stderr
    assert png_size(path.with_suffix(".png")) == (400, 300)


def test_periods_selects_the_first_periods(trajectory_file):
    path, _ = trajectory_file
    traj = vibromap_h5.read_trajectory(path)
    mask = plot_trajectory.select_periods(traj, 1.0)
    assert mask.sum() == 201  # samples 0..200 of 200 per period, the end point included
    assert traj.phase[mask].max() == pytest.approx(1.0, rel=1e-15)
    assert plot_trajectory.select_periods(traj, None).all()
    assert plot_trajectory.select_periods(traj, 10.0).all()


def test_title_names_regime_and_kcon(trajectory_file):
    traj = vibromap_h5.read_trajectory(trajectory_file[0])
    assert plot_trajectory.title(traj) == "regime (1,1),  k_con = T/T_con = 1113,  T_con = 0.000781 s"


def one_line_error(result, *fragments):
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("plot_trajectory: error: ")
    for fragment in fragments:
        assert fragment in lines[0]


def test_missing_file_gives_exit_2_and_one_line(tmp_path):
    missing = tmp_path / "missing.h5"
    one_line_error(run([*SCRIPT, str(missing)]), str(missing), "no such file")
    assert not missing.with_suffix(".png").exists()


def test_non_hdf5_file_gives_exit_2_and_one_line(tmp_path):
    text = tmp_path / "notes.h5"
    text.write_text("not HDF5\n")
    one_line_error(run([*SCRIPT, str(text)]), str(text), "not an HDF5 file")


def test_hdf5_file_of_another_kind_gives_exit_2_and_one_line(tmp_path):
    other = tmp_path / "map.h5"
    with h5py.File(other, "w") as f:
        f.create_dataset("k_con", data=np.zeros((3, 3)))
    one_line_error(run([*SCRIPT, str(other)]), str(other), "not a vibromap trajectory file")


def test_empty_trajectory_gives_exit_2_and_one_line(tmp_path):
    empty = tmp_path / "empty.h5"
    conftest.write_trajectory_h5(empty, {name: np.zeros(0) for name in conftest.UNITS})
    one_line_error(run([*SCRIPT, str(empty)]), "no samples")


def test_unwritable_output_gives_exit_2_and_one_line(trajectory_file, tmp_path):
    out = tmp_path / "no_such_dir" / "fig.png"
    one_line_error(run([*SCRIPT, str(trajectory_file[0]), "-o", str(out)]), str(out))


def test_help_describes_the_options():
    result = run([*SCRIPT, "--help"])
    assert result.returncode == 0
    for option in ("TRAJ.h5", "--output", "--periods"):
        assert option in result.stdout


def test_missing_modules_give_a_one_line_hint_to_use_the_launcher(tmp_path):
    # Simulate an interpreter without h5py: a None entry in sys.modules makes the import fail.
    code = ("import sys, runpy; sys.modules['h5py'] = None; sys.argv = ['vibromap', 'plot_trajectory', 'x.h5']; "
            "runpy.run_module('vibromap', run_name='__main__')")
    result = run([sys.executable, "-c", code])
    assert result.returncode == 3
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and "vibromap-post plot_trajectory" in lines[0] and "h5py" in lines[0]


def test_the_launcher_is_executable():
    assert os.access(LAUNCHER, os.X_OK)
    with open(LAUNCHER) as f:
        assert f.readline() == "#!/usr/bin/env bash\n"


# ---- the launcher -------------------------------------------------------------------------


def test_launcher_prints_the_interpreter_it_is_given():
    result = run([LAUNCHER, "--print"], VIBROMAP_PYTHON=sys.executable)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == sys.executable


def test_launcher_falls_back_when_vibromap_python_is_broken(tmp_path):
    result = run([LAUNCHER, "--print"], VIBROMAP_PYTHON=str(tmp_path / "no-python"))
    assert result.returncode == 0, result.stderr
    interpreter = result.stdout.strip()
    assert os.path.isabs(interpreter) and interpreter != str(tmp_path / "no-python")
    assert "VIBROMAP_PYTHON" in result.stderr  # says it did not use the given one


def test_launcher_runs_the_script(trajectory_file, tmp_path):
    out = tmp_path / "via-launcher.png"
    result = run([LAUNCHER, "plot_trajectory", str(trajectory_file[0]), "-o", str(out)], VIBROMAP_PYTHON=sys.executable)
    assert result.returncode == 0, result.stderr
    assert png_size(out) == (1200, 900)


def test_launcher_rejects_an_unknown_script():
    result = run([LAUNCHER, "no_such_script"])
    assert result.returncode == 2
    assert result.stderr.splitlines() == ["vibromap-post: error: no postprocess script 'no_such_script' (see vibromap-post --help)"]
