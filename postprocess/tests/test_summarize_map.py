"""Tests of the script summarize_map (vibromap/_summarize_map.py) on maps written by make_map.py with known contents."""
import subprocess
import sys

import numpy as np

import conftest
import make_map
from vibromap import _summarize_map as summarize_map
from vibromap._io import read_map

AXES = [("E1", np.array([1e5, 1e7, 1e9]), "log"), ("R1", np.array([0.1, 1.0]), "lin")]
P11, NOC = make_map.REGIME["periodic"], make_map.REGIME["no_contact"]


def write(path, k_con, quantities=None, long_names=None):
    regime = np.array([[P11, P11], [P11, NOC], [NOC, NOC]], dtype=np.int8)
    n = np.where(regime == P11, 1, 0)
    wall = np.array([[0.1, 0.2], [0.3, 0.9], [0.05, 0.01]])
    make_map.write_map(path, AXES, regime, n, n, wall_s=wall, stable=np.ones((3, 2), np.int8),
                       quantities={"k_con": k_con, **(quantities or {})}, long_names=long_names)


def test_counts_and_slowest_cell_are_reported(tmp_path):
    path = tmp_path / "m.h5"
    write(path, np.full((3, 2), 5.0))
    lines, bad = summarize_map.summary_lines(read_map(str(path)), slowest=1)
    text = "\n".join(lines)
    assert bad == 0
    assert "6/6 cells done" in text
    assert "(1,1) 3" in text and "no-contact 3" in text
    assert "stable 6" in text
    assert "max 0.9 s" in text and "total 1.56 s" in text
    assert "slow: 0.9 s  E1=1e+07, R1=1" in text


def test_non_finite_value_in_a_computed_cell_fails(tmp_path):
    path = tmp_path / "m.h5"
    k_con = np.full((3, 2), 5.0)
    k_con[1, 0] = np.inf
    write(path, k_con)
    proc = subprocess.run([*conftest.script("summarize_map"), str(path)], capture_output=True, text=True)
    assert proc.returncode == 1
    assert "NON-FINITE: k_con in 1 computed cells" in proc.stdout


def test_nan_is_allowed_where_the_long_name_says_not_computed(tmp_path):
    """The file names the quantities whose NaN means "not computed" (their long_name), even one
    this reader has never heard of; any other NaN in a cell done is reported."""
    path = tmp_path / "m.h5"
    nan_in_one = np.full((3, 2), 1.5)
    nan_in_one[0, 1] = np.nan
    write(path, nan_in_one, quantities={"x1_max": nan_in_one, "lyapunov": nan_in_one},
          long_names={"k_con": "softness", "x1_max": "largest x1 of the cycle (NaN where not computed)",
                      "lyapunov": "largest Lyapunov exponent"})
    sweep = read_map(str(path))
    assert sweep.not_computed_as_nan() == ["x1_max"]
    lines, bad = summarize_map.summary_lines(sweep, slowest=0)
    assert bad == 2
    assert "NON-FINITE: k_con in 1 computed cells" in lines and "NON-FINITE: lyapunov in 1 computed cells" in lines
    assert not any("x1_max" in line for line in lines)


def test_missing_file_is_exit_2(tmp_path):
    proc = subprocess.run([*conftest.script("summarize_map"), str(tmp_path / "none.h5")],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1


def test_a_shooting_map_is_flagged_and_soft_and_hertz_invalid_cells_are_counted(tmp_path):
    """make_map's soft pattern: 4 soft cells of 23 done; 4 Hertz-invalid of the 22 with impacts."""
    path = tmp_path / "shooting.h5"
    arrays = make_map.write_soft_map(path, steady="shooting")
    proc = subprocess.run([*conftest.script("summarize_map"), str(path)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    done = arrays["regime"] != make_map.REGIME["not_computed"]
    impacts = done & (arrays["k_con"] > 0)
    assert (int(arrays["soft"][done].sum()), int((arrays["hertz_valid"][impacts] == 0).sum()), int(impacts.sum())) == (4, 4, 22)
    assert ("answer: some stable orbit (shooting), not necessarily the motion from rest; WARNING: a cell, soft or not, "
            'may not be what the system does from rest (analysis.steady = "follow" gives that motion)') in lines
    assert ("soft: 4 of 23 cells done (stable periodic with impacts, Hertz-valid, k_con <= 10; from the map's /soft)"
            in lines)  # fmt: skip
    assert "Hertz-invalid (z_max/R* > 0.05): 4 of 22 cells with impacts (from the map's hertz_valid)" in lines


def test_the_answer_kind_of_follow_and_integrate_maps(tmp_path):
    for steady, answer in (("follow", "the motion the initial state settles into (follow)"),
                           ("integrate", "the motion the initial state settles into, by brute-force integration (integrate)")):  # fmt: skip
        path = tmp_path / f"{steady}.h5"
        make_map.write_soft_map(path, steady=steady)
        lines, _ = summarize_map.summary_lines(read_map(str(path)), slowest=0)
        assert f"answer: {answer}" in lines and not any("WARNING" in line for line in lines)


def test_a_map_of_soft_cells_the_writer_computed_reports_them_from_its_soft(tmp_path):
    """make_map's /soft by the definition (stable, Hertz-valid, k_con 5 <= 10): the 3 periodic cells."""
    path = tmp_path / "m.h5"
    write(path, np.full((3, 2), 5.0))
    lines, bad = summarize_map.summary_lines(read_map(str(path)), slowest=0)
    assert bad == 0
    assert "soft: 3 of 6 cells done (stable periodic with impacts, Hertz-valid, k_con <= 10; from the map's /soft)" in lines
    assert "Hertz-invalid (z_max/R* > 0.05): 0 of 6 cells with impacts (from the map's hertz_valid)" in lines
