"""Tests of postprocess/plot_regime_map.py, and of what the map scripts plot_regime_map,
plot_kcon_map and plot_soft_map share (errors, help, launcher), on the map files of map_cases.py
(their patterns are described there). plot_kcon_map: test_plot_kcon_map.py."""

from __future__ import annotations

import os
import sys

import matplotlib.image
import numpy as np
import pytest

import conftest
from conftest import run, png_size, pixels_near
import make_map
from map_cases import (COUNTS_2D, E1_2D, E2_2D, KCON_SCRIPT, MIN_PNG_BYTES, R, REGIME_SCRIPT, SOFT_SCRIPT, LAUNCHER,
                       figure_texts, legend_texts, one_line_error, pattern_2d, soft_outlines)
from vibromap.plot import _kcon_map as plot_kcon_map
from vibromap.plot import _regime_map as plot_regime_map
from vibromap import _io as vibromap_h5


# ---- plot_regime_map ----------------------------------------------------------------------


def test_regime_plot_writes_a_png_with_the_regime_colours(map2d, tmp_path):
    out = tmp_path / "regimes.png"
    result = run([*REGIME_SCRIPT, str(map2d[0]), "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert result.stderr == "" and result.stdout == f"plot_regime_map: wrote {out}\n"
    assert png_size(out) == (1350, 900)  # 9 x 6 in at 150 dpi
    assert out.stat().st_size > MIN_PNG_BYTES
    image = matplotlib.image.imread(out)
    # 24 cells on roughly 1000 x 750 px: one cell is ~30,000 px.
    for color, cells in ((plot_regime_map.PERIODIC_COLORS[0], 6), (plot_regime_map.KIND_COLORS["chatter"], 6),
                         (plot_regime_map.KIND_COLORS["not-computed"], 2), (plot_regime_map.KIND_COLORS["failed"], 1)):
        assert pixels_near(image, color) > cells * 15_000, color  # fmt: skip


def test_regime_figure_legend_counts_log_axes_and_cell_edges(map2d):
    m = vibromap_h5.read_map(map2d[0])
    sl = plot_regime_map.choose_slice(m, None, None, {})
    fig = plot_regime_map.plot(m, sl)
    try:
        assert legend_texts(fig) == [f"{label}: {count} cell{'s' if count > 1 else ''}" for label, count in COUNTS_2D.items()]
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        assert "E1 (Young's modulus of body 1), Pa" == ax.get_xlabel()
        assert "all axes shown" in ax.get_title() and "partial run: 22 of 24 cells done" in ax.get_title()
        [mesh] = ax.collections
        corners = mesh.get_coordinates()  # (ny + 1, nx + 1, 2)
        np.testing.assert_allclose(corners[0, :, 0], 10.0 ** np.arange(4.5, 11.0), rtol=1e-12)
        np.testing.assert_allclose(corners[:, 0, 1], [1e3, 1e5, 1e7, 1e9, 1e11], rtol=1e-12)
        # Each label's colour: cell [i=0, j=0] is (1,1), the first periodic colour.
        colors = mesh.cmap(mesh.norm(mesh.get_array()))
        np.testing.assert_allclose(colors.reshape(4, 6, 4)[0, 0, :3], matplotlib.colors.to_rgb(plot_regime_map.PERIODIC_COLORS[0]))
        np.testing.assert_allclose(colors.reshape(4, 6, 4)[3, 5, :3], matplotlib.colors.to_rgb(plot_regime_map.KIND_COLORS["chatter"]))
    finally:
        matplotlib.pyplot.close(fig)


def test_a_categorical_law_axis_is_drawn_one_named_column_per_law(tmp_path):
    """contact.law as an axis: values are indices in the order swept (here flores, hertz), drawn
    at 0, 1, ... with the laws' names as ticks; the soft region's outline sits between the columns."""
    path = tmp_path / "law.h5"
    laws = ["hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier"]
    regime = np.zeros((2, 3), dtype=np.int8)
    k_con = np.array([[5.0, 20.0], [5.0, 20.0], [5.0, 20.0]]).T  # law x E2: soft under flores
    make_map.write_map(path, [("law", [3.0, 0.0], "lin"), ("E2", [1e4, 1e6, 1e8], "log")], regime,
                       np.ones((2, 3), dtype=np.int32), np.ones((2, 3), dtype=np.int32),
                       quantities={"k_con": k_con}, categories={"law": laws}, soft=k_con <= 10,
                       hertz_valid=np.ones((2, 3)))  # fmt: skip
    m = vibromap_h5.read_map(str(path))
    assert m.axes["law"].categories == laws and not m.axes["law"].is_log
    assert m.axes["law"].tick_labels() == ["flores", "hertz"]
    sl = plot_regime_map.choose_slice(m, "law", "E2", {})
    fig = plot_regime_map.plot(m, sl)
    try:
        ax = fig.axes[0]
        assert [t.get_text() for t in ax.get_xticklabels()] == ["flores", "hertz"]
        [mesh] = ax.collections
        np.testing.assert_allclose(mesh.get_coordinates()[0, :, 0], [-0.5, 0.5, 1.5])
    finally:
        matplotlib.pyplot.close(fig)
    info = vibromap_h5.add_soft_cells(m)
    fig = plot_kcon_map.plot(m, plot_regime_map.choose_slice(m, "law", "E2", {}), info)
    try:
        [outline] = soft_outlines(fig)
        # The soft column (flores) ends halfway between the two laws' columns.
        e2_edges = vibromap_h5.cell_edges(m.axes["E2"])
        assert any(np.allclose(segment, [[0.5, e2_edges[0]], [0.5, e2_edges[-1]]]) for segment in outline.get_segments())
    finally:
        matplotlib.pyplot.close(fig)


def test_regime_figure_hatches_the_unstable_cells(map2d, tmp_path):
    path, arrays = map2d
    stable = np.where(arrays["regime"] == R["periodic"], 1, -1)
    stable[1, 0] = stable[4, 1] = 0  # a (1,1) and a (2,1) cell unstable
    stable[0, 3] = 0  # not done: not hatched whatever its code
    hatched = tmp_path / "hatched.h5"
    make_map.write_map(hatched, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], arrays["regime"], arrays["n"],
                       arrays["k"], status=arrays["status"], stable=stable)  # fmt: skip
    m = vibromap_h5.read_map(hatched)
    sl = plot_regime_map.choose_slice(m, None, None, {})
    np.testing.assert_array_equal(np.argwhere(plot_regime_map.unstable_cells(sl)), [[0, 1], [1, 4]])
    fig = plot_regime_map.plot(m, sl)
    try:
        texts = legend_texts(fig)
        assert texts[:-1] == [f"{label}: {count} cell{'s' if count > 1 else ''}" for label, count in COUNTS_2D.items()]
        assert texts[-1] == "unstable orbit: 2 cells"
        mesh, hatch = fig.axes[0].collections
        assert hatch.get_hatch() == plot_regime_map.UNSTABLE_HATCH and len(hatch.get_paths()) == 2
        # Cell [E1 index 1, E2 index 0] spans E1 10^5.5..10^6.5, E2 10^3..10^5.
        corners = hatch.get_paths()[0].vertices
        np.testing.assert_allclose(corners[:4], [[10**5.5, 1e3], [10**6.5, 1e3], [10**6.5, 1e5], [10**5.5, 1e5]], rtol=1e-12)
    finally:
        matplotlib.pyplot.close(fig)
    # The hatch lines darken the hatched (1,1) cell but no unhatched one of that colour.
    out = tmp_path / "hatched.png"
    assert plot_regime_map.main([str(hatched), "-o", str(out)]) == 0
    plain = tmp_path / "plain.png"
    assert plot_regime_map.main([str(path), "-o", str(plain)]) == 0
    blue = plot_regime_map.PERIODIC_COLORS[0]
    lost = pixels_near(matplotlib.image.imread(plain), blue) - pixels_near(matplotlib.image.imread(out), blue)
    assert lost > 2_000, lost  # a cell is ~30,000 px; //// hatching covers a good part of it


def test_regime_figure_names_the_fixed_values(map3d):
    m = vibromap_h5.read_map(map3d[0])
    sl = plot_regime_map.choose_slice(m, "E2", "R1", {"E1": 1e7})
    fig = plot_regime_map.plot(m, sl)
    try:
        texts = figure_texts(fig)
        assert any("fixed: E1 = 1e+07 Pa" in text for text in texts), texts
        assert legend_texts(fig) == [f"({n},1): 3 cells" for n in range(1, 6)]
        assert fig.axes[0].get_xscale() == "log" and fig.axes[0].get_yscale() == "linear"
    finally:
        matplotlib.pyplot.close(fig)


def test_regime_script_fix_and_axes_options(map3d, tmp_path):
    out = tmp_path / "r.png"
    result = run([*REGIME_SCRIPT, str(map3d[0]), "--x", "R1", "--y", "E2", "--fix", "E1=3e6", "-o", str(out)])
    assert result.returncode == 0, result.stderr
    # log10(3e6) = 6.48: nearer 1e6 than 1e7 in log space.
    assert result.stdout.splitlines() == [
        "plot_regime_map: note: E1 = 3e+06 is not a grid value; using E1 = 1e+06 Pa",
        f"plot_regime_map: wrote {out}",
    ]
    assert png_size(out) == (1350, 900)


def test_regime_script_default_output_and_strip(map1d):
    result = run([*REGIME_SCRIPT, str(map1d)])
    assert result.returncode == 0, result.stderr
    out = map1d.with_name("map1d_regime.png")
    assert png_size(out) == (1350, 450)
    m = vibromap_h5.read_map(map1d)
    fig = plot_regime_map.plot(m, plot_regime_map.choose_slice(m, None, None, {}))
    try:
        assert legend_texts(fig) == ["(1,1): 3 cells", "chatter: 2 cells", "no-contact: 1 cell", "not-computed: 1 cell"]
        assert fig.axes[0].get_yticks().size == 0
    finally:
        matplotlib.pyplot.close(fig)


# ---- the map scripts: errors, help, launcher -------------------------------------------------

SCRIPTS = [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map"), (SOFT_SCRIPT, "plot_soft_map")]


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_missing_file_gives_exit_2_and_one_line(tmp_path, script, prog):
    missing = tmp_path / "missing.h5"
    one_line_error(run([*script, str(missing)]), prog, str(missing), "no such file")


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_not_a_map_gives_exit_2_and_one_line(trajectory_file, script, prog):
    one_line_error(run([*script, str(trajectory_file[0])]), prog, "not a vibromap map file")


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_unknown_axis_gives_exit_2_and_one_line(map3d, tmp_path, script, prog):
    out = tmp_path / "never.png"
    one_line_error(run([*script, str(map3d[0]), "--x", "omega2", "-o", str(out)]), prog, "no axis 'omega2'", "E1, E2, R1")
    one_line_error(run([*script, str(map3d[0]), "--fix", "m2=310", "-o", str(out)]), prog, "no axis 'm2' to fix")
    assert not out.exists()


def test_map_without_kcon_gives_exit_2_and_one_line(tmp_path):
    path = tmp_path / "no_kcon.h5"
    regime, n, k, _, _ = pattern_2d()
    make_map.write_map(path, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k, quantities={"F_max": np.ones(regime.shape)})
    one_line_error(run([*KCON_SCRIPT, str(path)]), "plot_kcon_map", "did not store k_con", "stored: hertz_valid F_max", "[sweep] store")
    assert not path.with_name("no_kcon_kcon.png").exists()


@pytest.mark.parametrize("script", [REGIME_SCRIPT, KCON_SCRIPT, SOFT_SCRIPT])
def test_bad_option_values_give_exit_2(map2d, script):
    result = run([*script, str(map2d[0]), "--fix", "E1"])
    assert result.returncode == 2 and "expected NAME=VALUE" in result.stderr
    if script == KCON_SCRIPT:
        result = run([*script, str(map2d[0]), "--threshold", "-1"])
        assert result.returncode == 2 and "--threshold must be a positive number" in result.stderr


def test_help_describes_the_options():
    result = run([*REGIME_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "NAME=VALUE", "--output", "not-computed", "middle"):
        assert fragment in result.stdout, fragment
    result = run([*KCON_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "--threshold", "1000", "rigid", "soft", "soft_kcon", "Hertz-valid"):
        assert fragment in result.stdout, fragment
    result = run([*SOFT_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "--output", "soft_kcon", "hertz_limit", "Hertz-invalid", "rigid"):
        assert fragment in result.stdout, fragment


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_missing_modules_give_a_one_line_hint_to_use_the_launcher(script, prog):
    code = (f"import sys, runpy; sys.modules['h5py'] = None; sys.argv = ['vibromap', '{prog}', 'x.h5']; "
            "runpy.run_module('vibromap', run_name='__main__')")
    result = run([sys.executable, "-c", code])
    assert result.returncode == 3
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and f"vibromap-post {prog}" in lines[0] and "h5py" in lines[0]


@pytest.mark.parametrize("prog, size", [("plot_regime_map", (1350, 900)), ("plot_kcon_map", (1350, 975))])
def test_launcher_runs_the_map_scripts(map3d, tmp_path, prog, size):
    out = tmp_path / f"{prog}.png"
    result = run([LAUNCHER, prog, str(map3d[0]), "--fix", "R1=1", "-o", str(out)], VIBROMAP_PYTHON=sys.executable)
    assert result.returncode == 0, result.stderr
    assert png_size(out) == size
    listing = run([LAUNCHER, "--help"])
    assert prog in listing.stdout.split()


def test_hatched_cells_are_covered_by_disjoint_rectangles_exactly():
    """mask_rectangles covers the mask's cells exactly, without overlap, in few rectangles: a block
    of cells is one rectangle, an L shape two."""
    rng = np.random.default_rng(7)
    for _ in range(200):
        mask = rng.random((int(rng.integers(1, 12)), int(rng.integers(1, 12)))) < rng.random()
        covered = np.zeros(mask.shape, dtype=int)
        for j0, j1, i0, i1 in plot_regime_map.mask_rectangles(mask):
            covered[j0:j1, i0:i1] += 1
        np.testing.assert_array_equal(covered, mask.astype(int))
    block = np.zeros((6, 8), dtype=bool)
    block[1:5, 2:7] = True
    assert plot_regime_map.mask_rectangles(block) == [(1, 5, 2, 7)]
    ell = np.array([[1, 1, 0], [1, 1, 0], [0, 1, 1]], dtype=bool)
    assert plot_regime_map.mask_rectangles(ell) == [(0, 2, 0, 2), (2, 3, 1, 3)]
