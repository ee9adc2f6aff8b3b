"""The options every picture script shares (vibromap/plot/_args.py), refused alike by each
before any file is read: an image resolution outside 20 to 1200 dpi (one of 10^5 dpi would ask
matplotlib for a picture of gigabytes) and a non-positive --periods. The scripts' main(argv) run
in this process; one case runs through the launcher as a user runs it."""

import importlib

import pytest

import conftest
from conftest import run

SCRIPTS = ["plot_regime_map", "plot_kcon_map", "plot_soft_map", "plot_census_map", "plot_basins", "plot_branch",
           "plot_orbit_diagram", "plot_optimise", "plot_trajectory", "plot_work_precision", "plot_restitution"]


def main_of(script: str):
    return importlib.import_module("vibromap.plot._" + script[len("plot_"):]).main


def refused(script: str, argv: list[str], capsys) -> str:
    """The last line a script's main printed when it refused argv with exit status 2."""
    with pytest.raises(SystemExit) as stop:
        main_of(script)(argv)
    assert stop.value.code == 2
    return capsys.readouterr().err.strip().splitlines()[-1]


@pytest.mark.parametrize("script", SCRIPTS)
@pytest.mark.parametrize("dpi", ["0", "19", "1201", "100000"])
def test_a_resolution_outside_20_to_1200_dpi_is_one_line_and_exit_2(script, dpi, tmp_path, capsys):
    out = tmp_path / "out.png"
    line = refused(script, [str(tmp_path / "missing.h5"), "-o", str(out), "--dpi", dpi], capsys)
    assert line == f"{script}: error: --dpi {dpi}: must be from 20 to 1200"
    assert not out.exists()


@pytest.mark.parametrize("script", ["plot_optimise", "plot_trajectory"])
@pytest.mark.parametrize("periods", ["0", "-1", "nan"])
def test_periods_must_be_positive(script, periods, tmp_path, capsys):
    line = refused(script, [str(tmp_path / "missing.h5"), "--periods", periods], capsys)
    assert line == f"{script}: error: --periods must be positive"


@pytest.mark.parametrize("script", SCRIPTS[:-1])  # plot_restitution has no default image name
def test_the_image_name_defaults_to_the_input_and_a_missing_input_is_named(script, tmp_path, capsys):
    """With -o left out, the script gets as far as reading its input, and names it in one line."""
    missing = tmp_path / "missing.h5"
    assert main_of(script)([str(missing)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{script}: error: {missing}")


def test_the_launcher_refuses_a_resolution_in_one_line(tmp_path):
    result = run([conftest.LAUNCHER, "plot_basins", str(tmp_path / "b.h5"), "--dpi", "100000"])
    assert result.returncode == 2
    assert result.stderr.strip().splitlines()[-1] == "plot_basins: error: --dpi 100000: must be from 20 to 1200"
