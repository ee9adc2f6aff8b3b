"""Tests of vibromap_curves.read_curves and of --curves in the map pictures (plot_regime_map,
plot_kcon_map, plot_soft_map, plot_census_map): curve files written by make_curves.py in the
layout of vibromap continue --curve, drawn over the maps of map_cases.py and test_plot_census.py.

The 2-D map (map_cases.py) has the axes E1 (log, 1e5..1e10, cell edges 10^4.5..10^10.5) and E2
(log, 1e4..1e10, edges 1e3..1e11), whose scene keys are contact.E1 and contact.E2.
"""
import os
import sys

import h5py
import matplotlib.colors
import matplotlib.pyplot as plt
import numpy as np
import pytest

import conftest
from conftest import run
from stamp import stamp
import make_curves
import make_map
from vibromap.plot import _census_map as plot_census_map
from vibromap.plot import _kcon_map as plot_kcon_map
from vibromap.plot import _regime_map as maps
from vibromap.plot import _soft_map as plot_soft_map
import test_plot_census
from map_cases import KCON_SCRIPT, REGIME_SCRIPT, SOFT_SCRIPT, legend_texts, one_line_error
from vibromap._io import FileVersionError, VibromapFileError, add_soft_cells, read_curves, read_map

X_EDGES, Y_EDGES = (10.0**4.5, 10.0**10.5), (1e3, 1e11)
FOLD = make_curves.curve("fold", [1e6, 1e7, 1e8, 1e9], [1e5, 1e6, 2e7, 1e9], n=1,
                         codim2=[(1e7, 1e6, "cusp")])  # fmt: skip
LEVEL = make_curves.curve("level:k_con=10", [2.5e5, 2.5e5, 3e5], [1e4, 1e6, 1e9], n=1,
                          codim2=[(2.5e5, 1e6, "fold+level:k_con=10")])  # fmt: skip
PD = make_curves.curve("period-doubling", [1e8, 1e10, 1e12], [1e8, 1e9, 1e10], n=2)  # leaves the map at E1 = 10^10.5
NS = make_curves.curve("neimark-sacker", [1e6, 1e7], [1e9, 1e8])
GRAZING = make_curves.curve("grazing", [2e5, 2e9], [3e4, 3e4], codim2=[(2e5, 3e4, "grazing+fold")])
# The grazing point of the fold, as the fold curve finds it: one point, one kind, one legend entry.
FOLD_GRAZING = make_curves.curve("fold", [2e5, 1e6], [3e4, 1e5], codim2=[(2e5, 3e4, "fold+grazing")])
LEVEL5 = make_curves.curve("level:k_con=5", [1e5, 1e6], [1e10, 1e9])


@pytest.fixture
def curve_files(tmp_path):
    """Two curve files in contact.E1 x contact.E2: (fold, level k_con=10, period-doubling) and
    (neimark-sacker, grazing, level k_con=5, another fold, meeting the grazing curve)."""
    first, second = tmp_path / "fold.h5", tmp_path / "more.h5"
    make_curves.write_curves(first, [FOLD, LEVEL, PD])
    make_curves.write_curves(second, [NS, GRAZING, LEVEL5, FOLD_GRAZING])
    return str(first), str(second)


def curve_lines(fig):
    return [line for ax in fig.axes for line in ax.get_lines() if line.get_gid() == maps.CURVE_GID]


def codim2_lines(fig):
    return [line for ax in fig.axes for line in ax.get_lines() if line.get_gid() == maps.CODIM2_GID]


# ---- read_curves ---------------------------------------------------------------------------


def test_read_curves_gives_every_curve_of_the_file_in_order(curve_files):
    curves = read_curves(curve_files[0])
    assert [c["kind"] for c in curves] == ["fold", "level:k_con=10", "period-doubling"]
    assert [c["group"] for c in curves] == ["curve_0", "curve_1", "curve_2"]
    fold = curves[0]
    assert (fold["param_name"], fold["param2_name"], fold["param_unit"], fold["param2_unit"]) == (
        "contact.E1", "contact.E2", "Pa", "Pa")  # fmt: skip
    assert fold["n"] == 1 and curves[2]["n"] == 2 and fold["stop"] == "left the box; left the box"
    np.testing.assert_array_equal(fold["param"], FOLD["param"])
    np.testing.assert_array_equal(fold["param2"], FOLD["param2"])
    np.testing.assert_array_equal(fold["k_con"], [10.0, 11.0, 12.0, 13.0])
    np.testing.assert_array_equal(fold["T_con"], 1.0 / np.array([10.0, 11.0, 12.0, 13.0]))
    np.testing.assert_array_equal(fold["stable"], [0, 1, 0, 1])
    np.testing.assert_array_equal(fold["F_max"], [1e5, 1.1e5, 1.2e5, 1.3e5])
    assert fold["stable"].dtype == np.int8
    assert fold["multipliers"].shape == (4, 4) and fold["multipliers"][0, 0] == pytest.approx(0.2 + 0.02j)
    assert fold["codim2"] == [{"param": 1e7, "param2": 1e6, "kind": "cusp"}]
    assert curves[2]["codim2"] == []


@pytest.mark.parametrize("version", [0, 2])
def test_a_curve_file_of_another_format_version_is_refused_naming_both_versions(map2d, tmp_path, version):
    path = tmp_path / "old.h5"
    make_curves.write_curves(path, [FOLD])
    stamp(path, "curve file", version=version)
    line = (f"{path}: a curve file of format version {version}; this vibromap reads version 1 only: make the file "
            "again with this vibromap")
    with pytest.raises(FileVersionError) as error:
        read_curves(path)
    assert str(error.value) == line
    out = tmp_path / "out.png"
    result = run([*REGIME_SCRIPT, str(map2d[0]), "--curves", str(path), "-o", str(out)])
    one_line_error(result, "plot_regime_map", line)
    assert not out.exists()


@pytest.mark.parametrize(
    "change, message",
    [
        ({"attributes": {"vibromap_file": "branch"}}, "not a curve file of vibromap continue --curve (it is a 'branch' file)"),
        ({"attributes": {"vibromap_file": None}}, 'not a curve file of vibromap continue --curve (no root attribute '
                                                  'vibromap_file = "curves")'),
        ({"drop": "F_max"}, "curve_0 has no dataset 'F_max'"),
        ({"drop": "codim2"}, "curve_0 has no group 'codim2'"),
        ({"attributes": {"param2": None}}, "not a curve file of vibromap continue --curve (no root attribute 'param2', "
                                           "the key of the plane's axis)"),
        ({"drop": "param2"}, "curve_0 has no dataset 'param2'"),
        ({"short": "k_con"}, "dataset 'curve_0/k_con' has 3 values, not the curve's 4"),
        ({"kind": ""}, "curve_0 has no attribute 'kind' (fold, period-doubling, ..., level:NAME=VALUE)"),
    ],
)  # fmt: skip
def test_read_curves_refuses_a_file_that_is_not_a_curve_file_in_one_line(tmp_path, change, message):
    path = tmp_path / "bad.h5"
    fold = dict(FOLD, kind=change.get("kind", "fold"))
    make_curves.write_curves(path, [fold], attributes=change.get("attributes"))
    with h5py.File(path, "a") as f:
        if "drop" in change:
            del f["curve_0"][change["drop"]]
        if "short" in change:
            del f["curve_0"][change["short"]]
            f["curve_0"].create_dataset(change["short"], data=np.ones(3))
    stamp(path, "curve file")
    with pytest.raises(VibromapFileError) as error:
        read_curves(path)
    assert str(error.value) == f"{path}: {message}"


def test_read_curves_names_a_map_given_as_a_curve_file(map2d):
    with pytest.raises(VibromapFileError) as error:
        read_curves(map2d[0])
    assert str(error.value) == (f"{map2d[0]}: not a curve file of vibromap continue --curve (no root attribute "
                                "vibromap_file = \"curves\")")  # fmt: skip


# ---- the curves over a map ------------------------------------------------------------------


def test_the_regime_map_draws_every_curve_through_its_points_with_a_legend_entry_per_kind(map2d, curve_files):
    m = read_map(map2d[0])
    sl = maps.choose_slice(m, None, None, {})
    fig = maps.plot(m, sl, maps.read_curve_files(list(curve_files)))
    try:
        lines = curve_lines(fig)
        drawn = [FOLD, LEVEL, PD, NS, GRAZING, LEVEL5, FOLD_GRAZING]
        assert len(lines) == len(drawn)
        for line, c in zip(lines, drawn):
            np.testing.assert_array_equal(line.get_xdata(), c["param"])
            np.testing.assert_array_equal(line.get_ydata(), c["param2"])
        styles = {c["kind"]: (line.get_color(), line.get_linestyle()) for line, c in zip(lines, drawn)}
        assert len(set(styles.values())) == 6  # one colour and line style per kind; the second fold as the first
        assert styles["fold"] == ("#000000", "-") and styles["level:k_con=10"] == (maps.LEVEL_COLORS[0], "--")
        assert styles["level:k_con=5"] == (maps.LEVEL_COLORS[1], "--") and styles["period-doubling"][1] == "-."
        texts = legend_texts(fig)
        curve_entries = ["fold curve", "level curve k_con=10", "period-doubling curve", "neimark-sacker curve",
                         "grazing curve", "level curve k_con=5", "codim-2 point: cusp",
                         "codim-2 point: fold+level:k_con=10", "codim-2 point: fold+grazing"]  # fmt: skip
        assert texts[-len(curve_entries):] == curve_entries
        assert texts[0] == "(1,1): 6 cells"  # the regimes first, as without curves
        markers = codim2_lines(fig)
        assert [(list(line.get_xdata()), list(line.get_ydata())) for line in markers] == [
            ([1e7], [1e6]), ([2.5e5], [1e6]), ([2e5, 2e5], [3e4, 3e4])]  # grazing+fold and fold+grazing: one kind
        assert len({line.get_marker() for line in markers}) == 3
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        np.testing.assert_allclose(ax.get_xlim(), X_EDGES, rtol=1e-12)  # the period-doubling curve goes to 1e12:
        np.testing.assert_allclose(ax.get_ylim(), Y_EDGES, rtol=1e-12)  # clipped at the map's edge
        assert all(line.get_clip_on() for line in lines + markers)
    finally:
        plt.close(fig)


def test_the_curves_are_swapped_when_the_plot_has_their_keys_the_other_way_round(map2d, curve_files):
    m = read_map(map2d[0])
    sl = maps.choose_slice(m, "E2", "E1", {})
    fig = maps.plot(m, sl, maps.read_curve_files([curve_files[0]]))
    try:
        lines = curve_lines(fig)
        assert len(lines) == 3
        for line, c in zip(lines, (FOLD, LEVEL, PD)):
            np.testing.assert_array_equal(line.get_xdata(), c["param2"])
            np.testing.assert_array_equal(line.get_ydata(), c["param"])
        [cusp, fold_level] = codim2_lines(fig)
        assert (list(cusp.get_xdata()), list(cusp.get_ydata())) == ([1e6], [1e7])
        np.testing.assert_allclose(fig.axes[0].get_xlim(), Y_EDGES, rtol=1e-12)
    finally:
        plt.close(fig)


def test_curves_over_a_map_whose_axes_keep_their_keys_and_mix_log_and_linear_axes(tmp_path):
    """The census map E1 (log) x R1 (lin), its axes with their scene keys: a curve in
    contact.R1 x contact.E1 drawn with x = E1, y = R1 (swapped), the axes' scales kept."""
    path = tmp_path / "census.h5"
    test_plot_census.census_map(path)
    curves = tmp_path / "r1.h5"
    fold = make_curves.curve("fold", [0.2, 0.5, 0.9], [2e5, 1e7, 5e8])
    make_curves.write_curves(curves, [fold], param="contact.R1", param2="contact.E1", units=("m", "Pa"))
    m = read_map(str(path))
    sl = maps.choose_slice(m, None, None, {})
    fig = plot_census_map.plot_map(m, sl, "attractors", maps.read_curve_files([str(curves)]))
    try:
        [line] = curve_lines(fig)
        np.testing.assert_array_equal(line.get_xdata(), fold["param2"])
        np.testing.assert_array_equal(line.get_ydata(), fold["param"])
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "linear"
        assert "fold curve" in legend_texts(fig)
    finally:
        plt.close(fig)


def test_the_kcon_and_soft_maps_draw_the_curves_too(curve_files, tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    m = read_map(str(path))
    info = add_soft_cells(m)
    sl = maps.choose_slice(m, None, None, {})
    files = maps.read_curve_files(list(curve_files))
    for plot in (plot_kcon_map.plot, plot_soft_map.plot):
        fig = plot(m, sl, info, files)
        try:
            lines = curve_lines(fig)
            assert len(lines) == 7
            np.testing.assert_array_equal(lines[1].get_xdata(), LEVEL["param"])
            texts = legend_texts(fig)
            assert "level curve k_con=10" in texts and "grazing curve" in texts and texts.count("fold curve") == 1
        finally:
            plt.close(fig)


def test_a_curve_in_other_keys_is_refused_naming_the_file_the_keys_and_the_axes(map2d, tmp_path):
    curves = tmp_path / "omega.h5"
    make_curves.write_curves(curves, [FOLD], param="forcing.omega", param2="forcing.F0", units=("rad/s", "N"))
    for script in (REGIME_SCRIPT, KCON_SCRIPT, SOFT_SCRIPT):
        out = tmp_path / "out.png"
        result = run([*script, str(map2d[0]), "--curves", str(curves), "-o", str(out)])
        prog = script[-1]
        one_line_error(result, prog, f"{curves}: curve_0 (fold) is a curve in forcing.omega and forcing.F0, but the "
                                     "plot's axes are contact.E1 (x) and contact.E2 (y); draw it over a map of these two keys")  # fmt: skip
        assert not out.exists()


def test_a_curve_over_a_strip_is_refused(map1d, curve_files, tmp_path):
    out = tmp_path / "strip.png"
    result = run([*REGIME_SCRIPT, str(map1d), "--curves", curve_files[0], "-o", str(out)])
    one_line_error(result, "plot_regime_map", f"{curve_files[0]}: curve_0 (fold) is a curve in contact.E1 and "
                                              "contact.E2, but the plot's axes are contact.E2 (x);")  # fmt: skip
    assert not out.exists()


def test_the_scripts_take_curves_repeated_and_name_a_bad_curve_file(map2d, curve_files, tmp_path):
    out = tmp_path / "both.png"
    result = run([*REGIME_SCRIPT, str(map2d[0]), "--curves", curve_files[0], "--curves",
                  curve_files[1], "-o", str(out)])  # fmt: skip
    assert result.returncode == 0 and result.stdout == f"plot_regime_map: wrote {out}\n", result.stderr
    result = run([*KCON_SCRIPT, str(map2d[0]), "--curves", str(map2d[0]), "-o", str(out)])
    one_line_error(result, "plot_kcon_map", f"{map2d[0]}: not a curve file of vibromap continue --curve")
    result = run([*KCON_SCRIPT, str(map2d[0]), "--curves", str(tmp_path / "none.h5"), "-o", str(out)])
    one_line_error(result, "plot_kcon_map", f"{tmp_path / 'none.h5'}: no such file")


def test_census_cell_pictures_refuse_curves(tmp_path, curve_files):
    path = tmp_path / "census.h5"
    test_plot_census.census_map(path)
    result = run([*test_plot_census.SCRIPT, str(path), "--show", "cell", "--curves", curve_files[0]])
    assert result.returncode == 2 and "--curves draws over a map: not with --show cell" in result.stderr
