"""Tests of postprocess/plot_work_precision.py on a synthetic accuracy-study CSV in the layout of
src/campaigns/accuracy/accuracy_run.cpp (vibromap accuracy --csv)."""

from __future__ import annotations

import math
import os
import sys

import matplotlib.pyplot as plt
import pytest

import conftest
from conftest import run, png_size
from vibromap.plot import _work_precision as wp

SCRIPT = conftest.script("plot_work_precision")

HEADER = (
    "method,setting,integrator,steady,rtol,atol,rk4_steps,status,regime,regime_matches,steady_used,"
    "newton_iterations,wall_s,rhs_evals,steps,periods,T_con,F_max,k_con,rel_err_T_con,rel_err_F_max,"
    "rel_err_k_con,note"
)

# (method, setting, status, regime_matches, wall_s, rel_err_T_con, rel_err_F_max): errors fall
# 100x per case; rk4 at 2^11 failed (nan), so it is not drawn; dopri5 1e-8 has another regime.
CASES = [
    ("rk4", "2^11 steps/T", "failed", 0, 0.01, math.nan, math.nan),
    ("rk4", "2^12 steps/T", "ok", 1, 0.4, 2e-8, 3e-7),
    ("rk4", "2^13 steps/T", "ok", 1, 0.8, 5e-9, 6e-8),
    ("dopri5", "rtol 1e-6", "ok", 1, 0.002, 7e-6, 1e-4),
    ("dopri5", "rtol 1e-8", "ok", 0, 0.01, 9e-8, 1e-6),
    ("dopri5", "rtol 1e-10", "ok", 1, 0.04, 7e-10, 1e-8),
    ("hybrid+shooting", "rtol 1e-6", "ok", 1, 0.0008, 6e-9, 8e-8),
    ("hybrid+shooting", "rtol 1e-8", "ok", 1, 0.0013, 5e-10, 5e-9),
    ("hybrid+shooting", "rtol 1e-10", "ok", 1, 0.0028, 7e-11, 8e-10),
]
T = 0.869


def csv_line(method, setting, status, matches, wall_s, err_t, err_f) -> str:
    rk4 = method == "rk4"
    rtol = "nan" if rk4 else setting.split()[1]
    t_con = 0.097 * (1 + err_t) if math.isfinite(err_t) else 0.0
    f_max = 5590.0 * (1 + err_f) if math.isfinite(err_f) else 0.0
    k_con = T / t_con if t_con > 0 else 0.0
    err_k = err_t / (1 + err_t) if math.isfinite(err_t) else math.nan
    regime = "(1,1)" if matches else "(2,1)"
    fields = [method, setting, "rk4" if rk4 else "dopri5", "integrate", rtol, "nan", "2048" if rk4 else "0", status,
              f'"{regime}"', str(matches), "integrate", "0", repr(wall_s), "1000", "100", "50", repr(t_con), repr(f_max),
              repr(k_con), repr(err_t), repr(err_f), repr(err_k), ""]
    return ",".join(fields)


@pytest.fixture
def study_csv(tmp_path):
    path = tmp_path / "study.csv"
    lines = [HEADER, csv_line("reference", "rtol 1e-13", "ok", 1, 0.2, 0.0, 0.0)]
    lines += [csv_line(*c) for c in CASES]
    path.write_text("\n".join(lines) + "\n")
    return path


def method_lines(fig) -> dict[str, object]:
    return {line.get_gid().split(":", 1)[1]: line for line in fig.axes[0].get_lines()
            if (line.get_gid() or "").startswith("method:")}


def expected_points(method: str, column: int) -> tuple[list[float], list[float]]:
    rows = [c for c in CASES if c[0] == method and math.isfinite(c[column])]
    return [c[4] for c in rows], [c[column] for c in rows]


# ---- the reader and the figure, in process ----------------------------------------------


def test_reader_separates_the_reference(study_csv):
    study = wp.read_study(str(study_csv))
    assert study.reference is not None and study.reference.setting == "rtol 1e-13"
    assert [c.method for c in study.cases] == [c[0] for c in CASES]
    assert study.cases[4].regime_matches is False
    assert math.isnan(study.cases[0].errors["T_con"])
    assert study.cases[3].errors["F_max"] == 1e-4


@pytest.mark.parametrize("quantity,column", [("T_con", 5), ("F_max", 6)])
def test_one_line_per_method_with_its_points_on_log_axes(study_csv, quantity, column):
    fig = wp.plot(wp.read_study(str(study_csv)), quantity)
    try:
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        lines = method_lines(fig)
        assert sorted(lines) == ["dopri5", "hybrid+shooting", "rk4"]
        for method, line in lines.items():
            x, y = expected_points(method, column)
            assert list(line.get_xdata()) == x, method
            assert list(line.get_ydata()) == pytest.approx(y, rel=1e-12), method
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert labels[:3] == ["rk4 (steps per period)", "dopri5 (rtol)", "hybrid+shooting (rtol)"]
        assert "regime differs from the reference" in labels
        notes = sorted(t.get_text() for t in ax.texts)
        assert notes == sorted(["2^12", "2^13", "1e-6", "1e-8", "1e-10", "1e-6", "1e-8", "1e-10"])
        assert quantity in ax.get_ylabel() and "rtol 1e-13" in ax.get_title()
        assert any("rk4 2^11 (failed)" in t.get_text() for t in fig.texts)  # what is not drawn is named
    finally:
        plt.close(fig)


def test_regime_mismatch_is_ringed(study_csv):
    fig = wp.plot(wp.read_study(str(study_csv)), "T_con")
    try:
        rings = [line for line in fig.axes[0].get_lines() if line.get_gid() == "mismatch:dopri5"]
        assert len(rings) == 1
        assert list(rings[0].get_xdata()) == [0.01] and list(rings[0].get_ydata()) == [9e-8]
    finally:
        plt.close(fig)


# ---- the script -------------------------------------------------------------------------


def test_script_writes_a_png(study_csv, tmp_path):
    out = tmp_path / "wp.png"
    result = run([*SCRIPT, str(study_csv), "-o", str(out), "--quantity", "k_con"])
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    assert png_size(out) == (1200, 900)  # 8 x 6 in at 150 dpi
    assert out.stat().st_size > 20_000


def test_default_output_is_next_to_the_input(study_csv):
    result = run([*SCRIPT, str(study_csv), "--dpi", "50"])
    assert result.returncode == 0, result.stderr
    assert png_size(study_csv.with_suffix(".png")) == (400, 300)


def one_line_error(result, *fragments):
    assert result.returncode == 2, result.stderr
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("plot_work_precision: error: ")
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


def test_missing_file_gives_exit_2(tmp_path):
    missing = tmp_path / "missing.csv"
    one_line_error(run([*SCRIPT, str(missing)]), str(missing), "no such file")
    assert not missing.with_suffix(".png").exists()


def test_csv_of_another_kind_gives_exit_2(tmp_path):
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    one_line_error(run([*SCRIPT, str(other)]), str(other), "no column 'method'")


def test_bad_number_gives_exit_2_naming_the_line(study_csv):
    text = study_csv.read_text().replace("0.0013", "fast")
    study_csv.write_text(text)
    one_line_error(run([*SCRIPT, str(study_csv)]), f"{study_csv}:10", "wall_s 'fast' is not a number")


def test_nothing_to_draw_gives_exit_2(tmp_path):
    path = tmp_path / "none.csv"
    path.write_text("\n".join([HEADER, csv_line("reference", "rtol 1e-13", "ok", 1, 0.2, 0.0, 0.0),
                               csv_line("rk4", "2^11 steps/T", "failed", 0, 0.01, math.nan, math.nan)]) + "\n")
    one_line_error(run([*SCRIPT, str(path)]), "no case has a finite positive error of T_con")


def test_bad_quantity_is_a_usage_error(study_csv):
    result = run([*SCRIPT, str(study_csv), "--quantity", "z_max"])
    assert result.returncode == 2
    assert "--quantity" in result.stderr


def test_help_describes_the_options():
    result = run([*SCRIPT, "--help"])
    assert result.returncode == 0
    for option in ("CSV", "--output", "--quantity", "T_con", "F_max", "k_con", "vibromap accuracy"):
        assert option in result.stdout

