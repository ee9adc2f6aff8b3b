"""Tests of postprocess/plot_kcon_map.py on the map files of map_cases.py (their patterns are
described there) and on maps made for each test."""

from __future__ import annotations

import sys

import h5py
import matplotlib.image
import numpy as np

import conftest
from conftest import run, png_size, pixels_near
import make_map
from map_cases import (KCON_SCRIPT, MIN_PNG_BYTES, R, REGIME_SCRIPT, SOFT_DEFINITION, SOFT_SCRIPT, figure_texts,
                       legend_texts, soft_outlines)
from vibromap.plot import _kcon_map as plot_kcon_map
from vibromap.plot import _regime_map as plot_regime_map
from vibromap import _io as vibromap_h5


# ---- plot_kcon_map ------------------------------------------------------------------------


def kcon_figure(path, x=None, y=None, fixed=None, threshold=None):
    """(map, slice, figure) as plot_kcon_map's main draws them."""
    m = vibromap_h5.read_map(path)
    info = vibromap_h5.add_soft_cells(m, threshold)
    sl = plot_regime_map.choose_slice(m, x, y, fixed or {})
    return m, sl, plot_kcon_map.plot(m, sl, info)


def test_kcon_figure_outlines_the_soft_cells_and_no_hertz_invalid_one(tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    m, sl, fig = kcon_figure(path)
    try:
        [outline] = soft_outlines(fig)
        segments = outline.get_segments()
        x_edges, y_edges = vibromap_h5.cell_edges(sl.x), vibromap_h5.cell_edges(sl.y)
        points = np.concatenate(segments)
        assert np.all(np.isclose(points[:, 0, None], x_edges).any(axis=1)), "outline off the cell edges"
        assert np.all(np.isclose(points[:, 1, None], y_edges).any(axis=1)), "outline off the cell edges"
        e1, e2 = make_map.SOFT_AXES[0][1], make_map.SOFT_AXES[1][1]
        for i, j in np.ndindex(len(e1), len(e2)):
            # A log cell's centre is its grid value: inside the outline exactly for the soft cells.
            assert conftest.inside(segments, (e1[i], e2[j])) == ((i, j) in make_map.SOFT_CELLS), (i, j)
        # The Hertz-invalid cells with k_con 2 and 6 (<= 10) are outside it.
        assert all(m.data["k_con"][cell] <= 10 for cell in make_map.SOFT_HERTZ_INVALID[:2])
        [hatched] = [c for c in fig.axes[0].collections if c.get_gid() == plot_kcon_map.HERTZ_GID]
        assert len(hatched.get_paths()) == 4 and hatched.get_hatch() == plot_kcon_map.HERTZ_HATCH
        [mesh] = [c for c in fig.axes[0].collections if isinstance(c.norm, matplotlib.colors.LogNorm)]
        assert (mesh.norm.vmin, mesh.norm.vmax) == (2.0, 486.0)
        assert mesh.get_array().mask.sum() == 1 + 1  # no contact, not computed
        assert legend_texts(fig) == [f"{SOFT_DEFINITION} (outlined): 4 cells", "Hertz-invalid (z_max/R* > 0.05): 4 cells",
                                     "no contact: 1 cell", "not computed: 1 cell"]  # fmt: skip
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_key_tells_no_contact_from_non_periodic_cells(tmp_path):
    """The soft map with [0, 3] no contact, [1, 3] chaotic, [2, 3] quasi-periodic, [3, 3]
    permanent contact, [4, 3] failed (k_con NaN in all but the first, 0 there): each reason its
    own colour and legend entry (they were all one grey "no impact / no k_con")."""
    path = tmp_path / "reasons.h5"
    arrays = make_map.soft_pattern()
    regime, k_con = arrays["regime"].copy(), arrays["k_con"].copy()
    for cell, kind in (((1, 3), "chaotic"), ((2, 3), "quasi_periodic"), ((3, 3), "permanent_contact"), ((4, 3), "failed")):
        regime[cell], k_con[cell] = R[kind], np.nan
    n = np.where(regime == R["periodic"], 1, 0)
    make_map.write_soft_map(path, regime=regime, k_con=k_con, n=n, k=n.copy())
    m, sl, fig = kcon_figure(path)
    try:
        assert legend_texts(fig)[2:] == ["no contact: 1 cell", "permanent contact (no impact): 1 cell",
                                         "not periodic (quasi-periodic, chaotic): no k_con: 2 cells",
                                         "unresolved or failed: no k_con: 1 cell", "not computed: 1 cell"]  # fmt: skip
        [mesh] = [c for c in fig.axes[0].collections if c.get_gid() == plot_kcon_map.NO_KCON_GID]
        colors = {}
        rgba = mesh.to_rgba(mesh.get_array()).reshape(sl.data["regime"].shape + (4,))
        for cell, kind in (((0, 3), "no_contact"), ((1, 3), "chaotic"), ((2, 3), "quasi_periodic"),
                           ((3, 3), "permanent_contact"), ((4, 3), "failed"), ((5, 2), "not_computed")):  # fmt: skip
            j, i = (cell[1], cell[0]) if sl.x.name == make_map.SOFT_AXES[0][0] else cell
            colors[kind] = matplotlib.colors.to_hex(rgba[j, i])
        assert colors["no_contact"] == plot_kcon_map.COLOR_NO_CONTACT
        assert colors["chaotic"] == colors["quasi_periodic"] == "#e377c2"
        assert len({colors[k] for k in ("no_contact", "chaotic", "permanent_contact", "failed", "not_computed")}) == 5
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_figure_takes_the_limits_from_the_map(tmp_path):
    """hertz_limit 0.3 and soft_kcon 20: the z_ratio 0.2 cells are valid, k_con 18 is soft."""
    path = tmp_path / "limits.h5"
    arrays = make_map.soft_pattern()
    soft = (arrays["regime"] == R["periodic"]) & (arrays["stable"] == 1) & (arrays["k_con"] <= 20)
    make_map.write_soft_map(path, hertz_limit=0.3, soft_kcon=20.0, hertz_valid=np.ones((6, 4), np.int64), soft=soft)
    m, _, fig = kcon_figure(path)
    try:
        texts = legend_texts(fig)
        assert texts[:2] == [f"soft: stable periodic with impacts, Hertz-valid, k_con <= 20 (outlined): {int(soft.sum())} cells",
                             "Hertz-invalid (z_max/R* > 0.3): 0 cells"]  # fmt: skip
        assert not [c for c in fig.axes[0].collections if c.get_gid() == plot_kcon_map.HERTZ_GID]
        colorbar = fig.axes[2]
        assert [line.get_ydata()[0] for line in colorbar.get_lines()] == [20.0]
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_threshold_option_recomputes_the_soft_cells(tmp_path):
    path = tmp_path / "soft.h5"
    arrays = make_map.write_soft_map(path)
    m = vibromap_h5.read_map(path)
    info = vibromap_h5.add_soft_cells(m, 20.0)
    expected = ((arrays["regime"] == R["periodic"]) & (arrays["stable"] == 1) & (arrays["hertz_valid"] == 1)
                & (arrays["k_con"] <= 20))  # fmt: skip
    np.testing.assert_array_equal(m.data[vibromap_h5.SOFT_KEY] == 1, expected)
    assert info.soft_source == "computed from regime, stable, hertz_valid and k_con" and expected.sum() == 4 + 4  # k_con 18 added
    out = tmp_path / "k20.png"
    result = run([*KCON_SCRIPT, str(path), "--threshold", "20", "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        "plot_kcon_map: note: soft cells computed from regime, stable, hertz_valid and k_con "
        "(soft: stable periodic with impacts, Hertz-valid, k_con <= 20)",
        f"plot_kcon_map: wrote {out}",
    ]


def test_kcon_figure_of_a_map_without_a_soft_cell_says_so(map3d):
    """map3d's orbits have no known stability (the writer's default): no cell is soft."""
    _, _, fig = kcon_figure(map3d[0], "E1", "E2", {"R1": 0.1})
    try:
        assert soft_outlines(fig) == []
        assert legend_texts(fig)[:2] == [f"no soft cell here ({SOFT_DEFINITION})", "Hertz-invalid (z_max/R* > 0.05): 0 cells"]
        assert any("fixed: R1 = 0.1 m" in t for t in figure_texts(fig))
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_strip_outlines_the_soft_cells(map1d, tmp_path):
    """map1d with /soft: the (1,1) cells at E2 = 1e5, 1e6, 1e7 (k_con 1, 3.16, 10) are soft."""
    with h5py.File(map1d, "a") as f:
        f["soft"][...] = np.array([1, 1, 1, 0, 0, 0, -1], dtype=np.int8)
    make_map.seal(map1d)
    _, _, fig = kcon_figure(map1d)
    try:
        [outline] = soft_outlines(fig)
        segments = sorted(map(tuple, (tuple(map(tuple, s.tolist())) for s in outline.get_segments())))
        left, right = 10**4.5, 10**7.5
        expected = [((left, 0.0), (left, 1.0)), ((left, 0.0), (right, 0.0)), ((left, 1.0), (right, 1.0)), ((right, 0.0), (right, 1.0))]
        np.testing.assert_allclose(np.array(segments), np.array(sorted(expected)), rtol=1e-12)
    finally:
        matplotlib.pyplot.close(fig)
    out = tmp_path / "strip.png"
    result = run([*KCON_SCRIPT, str(map1d), "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert png_size(out) == (1350, 525)


def test_kcon_one_cell_wide_slices_and_a_map_with_nothing_done(tmp_path):
    path = tmp_path / "thin.h5"
    axes = [("m2", np.array([100.0, 200.0, 310.0]), "lin"), ("k2", np.array([4000.0]), "log")]
    make_map.write_map(path, axes, np.zeros((3, 1), int), np.ones((3, 1)), np.ones((3, 1)),
                       quantities={"k_con": np.array([[3.0], [10.0], [30.0]])}, soft=np.array([[1], [1], [0]]),
                       hertz_valid=np.ones((3, 1)), attributes={"soft_kcon": 10.0})  # fmt: skip
    m = vibromap_h5.read_map(path)
    k2_edges = vibromap_h5.cell_edges(m.axes["k2"])
    # The soft cells m2 = 100, 200 end at the edge m2 = 255, whichever way the slice lies.
    for x, y, edge in (("m2", "k2", [[255.0, k2_edges[0]], [255.0, k2_edges[1]]]),
                       ("k2", "m2", [[k2_edges[0], 255.0], [k2_edges[1], 255.0]])):  # fmt: skip
        _, _, fig = kcon_figure(path, x, y)
        try:
            [outline] = soft_outlines(fig)
            assert len(outline.get_segments()) == 4
            assert any(np.allclose(segment, edge, rtol=1e-12) for segment in outline.get_segments())
        finally:
            matplotlib.pyplot.close(fig)

    empty = tmp_path / "empty.h5"
    make_map.write_map(empty, axes, np.full((3, 1), -1), np.zeros((3, 1)), np.zeros((3, 1)), quantities={"k_con": np.ones((3, 1))},
                       soft=np.zeros((3, 1)), hertz_valid=np.zeros((3, 1)))  # fmt: skip
    m, _, fig = kcon_figure(empty)
    assert vibromap_h5.regime_counts(m.labels()) == {"not-computed": 3}
    try:
        assert soft_outlines(fig) == []
        assert legend_texts(fig) == ["no cell with an impact in this slice", f"no soft cell here ({SOFT_DEFINITION})",
                                     "Hertz-invalid (z_max/R* > 0.05): 0 cells", "not computed: 3 cells"]  # fmt: skip
    finally:
        matplotlib.pyplot.close(fig)
    for script in (REGIME_SCRIPT, KCON_SCRIPT, SOFT_SCRIPT):
        result = run([*script, str(empty), "-o", str(tmp_path / "empty.png")])
        assert result.returncode == 0, result.stderr


def test_kcon_script_writes_a_png(tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    result = run([*KCON_SCRIPT, str(path)])
    assert result.returncode == 0, result.stderr
    out = path.with_name("soft_kcon.png")
    assert result.stdout == f"plot_kcon_map: wrote {out}\n"
    assert png_size(out) == (1350, 975)
    assert out.stat().st_size > MIN_PNG_BYTES
    image = matplotlib.image.imread(out)
    assert pixels_near(image, plot_kcon_map.COLOR_SOFT_OUTLINE, tol=0.05) > 300  # the soft outline
    assert pixels_near(image, plot_kcon_map.COLOR_NOT_COMPUTED, tol=0.01) > 15_000
    assert pixels_near(image, plot_kcon_map.COLOR_NO_CONTACT, tol=0.01) > 15_000
