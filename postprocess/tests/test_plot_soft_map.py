"""Tests of the one definition of soft as the postprocess scripts read it (vibromap_h5's
add_soft_cells, cell_boundary, the root attributes soft_kcon, hertz_limit, steady) and of
postprocess/plot_soft_map.py. Maps come from make_map.write_soft_map (its soft_pattern: a 6 x 4
E1 x E2 map with soft, rigid, Hertz-invalid, unstable, chatter, no-contact and not-computed cells)
in the layout of include/vibromap/io/map_file.hpp, with or without the new /soft, /hertz_valid
and attributes."""

from __future__ import annotations

import os
import sys

import h5py
import matplotlib.image
import matplotlib.pyplot
import matplotlib.text
import numpy as np
import pytest

import conftest
from conftest import png_size, pixels_near, run
import make_map
from vibromap.plot import _census_map as plot_census_map
from vibromap.plot import _kcon_map as plot_kcon_map
from vibromap.plot import _regime_map as plot_regime_map
from vibromap.plot import _soft_map as plot_soft_map
from vibromap import _io as vibromap_h5

SCRIPT = conftest.script("plot_soft_map")
LAUNCHER = conftest.LAUNCHER
R, STABLE = make_map.REGIME, make_map.STABLE
SHOOTING_LINE = "answer: some stable orbit (shooting), not necessarily the motion from rest"


def texts(fig) -> list[str]:
    return [t.get_text() for t in fig.findobj(matplotlib.text.Text) if t.get_text()]


def legend_texts(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]


def soft_figure(path, x=None, y=None, fixed=None):
    """(map, slice, info, figure) as plot_soft_map's main draws them."""
    m = vibromap_h5.read_map(path)
    info = vibromap_h5.add_soft_cells(m)
    sl = plot_regime_map.choose_slice(m, x, y, fixed or {})
    return m, sl, info, plot_soft_map.plot(m, sl, info)


def expected_counts(a: dict) -> dict[str, int]:
    """The categories counted straight from the datasets of soft_pattern (soft_kcon 10, hertz_limit 0.05)."""
    done = a["regime"] != R["not_computed"]
    periodic = done & (a["regime"] == R["periodic"]) & (a["k"] > 0)
    stable = a["stable"] == STABLE["stable"]
    invalid = done & (a["hertz_valid"] == 0)
    would_be_soft = periodic & stable & (a["k_con"] > 0) & (a["k_con"] <= 10)
    valid = done & ~invalid
    return {
        "soft": int((valid & (a["soft"] == 1)).sum()),
        "rigid": int((valid & periodic & stable & (a["k_con"] > 10)).sum()),
        "invalid_soft": int((invalid & would_be_soft).sum()),
        "invalid": int((invalid & ~would_be_soft).sum()),
        "unstable": int((valid & periodic & (a["stable"] == STABLE["unstable"])).sum()),
        "no_impact": int((valid & (a["regime"] == R["no_contact"])).sum()),
        "not_periodic": int((valid & ~periodic & (a["regime"] != R["no_contact"])).sum()),
        "not_computed": int((~done).sum()),
    }


def test_make_map_writes_the_new_datasets_and_attributes(tmp_path):
    path = tmp_path / "soft.h5"
    arrays = make_map.write_soft_map(path, steady="shooting")
    m = vibromap_h5.read_map(path)
    done = arrays["regime"] != R["not_computed"]
    np.testing.assert_array_equal(m.data["soft"], np.where(done, arrays["soft"], -1))
    np.testing.assert_array_equal(m.data["hertz_valid"], np.where(done, arrays["hertz_valid"], 0))
    assert m.data["soft"].dtype == np.int8 and m.data["hertz_valid"].dtype == np.int64
    assert (m.soft_kcon, m.hertz_limit, m.steady) == (10.0, 0.05, "shooting")
    assert m.stored == ["hertz_valid", "k_con", "z_ratio"]  # /soft is always there; hertz_valid always stored
    assert m.answer_warning() == SHOOTING_LINE
    with h5py.File(path, "r") as f:
        assert f["soft"].attrs["flag_meanings"] == "not_computed no yes"
        assert [d[0].name for d in f["soft"].dims] == ["/E1", "/E2"]


@pytest.mark.parametrize("name, value", [("soft_kcon", -1.0), ("hertz_limit", "big"), ("steady", 3)])
def test_read_map_refuses_bad_soft_attributes(tmp_path, name, value):
    path = tmp_path / "bad.h5"
    make_map.write_soft_map(path, **{name: value})
    with pytest.raises(vibromap_h5.VibromapFileError, match=f"root attribute '{name}'"):
        vibromap_h5.read_map(path)


def test_add_soft_cells_takes_the_maps_own_soft_and_hertz_valid(tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    m = vibromap_h5.read_map(path)
    info = vibromap_h5.add_soft_cells(m)
    assert info.soft_source == "from the map's /soft" and info.overruled == 0
    soft = m.data[vibromap_h5.SOFT_KEY]
    assert sorted(map(tuple, np.argwhere(soft == 1).tolist())) == sorted(make_map.SOFT_CELLS)
    assert soft[5, 2] == -1 and m.data[vibromap_h5.HERTZ_KEY][5, 2] == -1  # not computed
    assert sorted(map(tuple, np.argwhere(m.data[vibromap_h5.HERTZ_KEY] == 0).tolist())) == sorted(make_map.SOFT_HERTZ_INVALID)


def test_another_soft_kcon_without_k_con_is_refused_rather_than_guessed(tmp_path):
    path = tmp_path / "no_kcon.h5"
    make_map.write_soft_map(path, quantities=("z_ratio",))
    m = vibromap_h5.read_map(path)
    assert vibromap_h5.add_soft_cells(m).soft_source == "from the map's /soft"  # its own soft_kcon: its /soft
    with pytest.raises(vibromap_h5.VibromapFileError) as error:
        vibromap_h5.add_soft_cells(m, 20.0)
    assert str(error.value) == f"{path}: cannot tell the soft cells for k_con <= 20: the map did not store k_con"


def test_a_hertz_invalid_cell_the_map_calls_soft_is_never_shown_soft(tmp_path):
    path = tmp_path / "wrong.h5"
    arrays = make_map.soft_pattern()
    soft = arrays["soft"].copy()
    soft[0, 0] = 1  # Hertz-invalid (z_ratio 0.2) with k_con 2
    make_map.write_soft_map(path, soft=soft)
    m, _, info, fig = soft_figure(path)
    try:
        assert info.overruled == 1 and m.data[vibromap_h5.SOFT_KEY][0, 0] == 0
        assert legend_texts(fig)[:3] == ["soft (k_con <= 10): 4 cells", "rigid: periodic with impacts, k_con > 10: 12 cells",
                                         "Hertz-invalid (z_max/R* > 0.05), would be soft: 2 cells"]  # fmt: skip
    finally:
        matplotlib.pyplot.close(fig)
    result = run([*SCRIPT, str(path), "-o", str(tmp_path / "wrong.png")])
    assert result.returncode == 0, result.stderr
    assert "plot_soft_map: note: 1 cell the map calls soft are Hertz-invalid: shown as not soft" in result.stdout


def test_cell_boundary_outlines_the_cells_of_a_mask():
    mask = np.array([[1, 1, 0], [0, 1, 0]], dtype=bool)  # (ny, nx): an L of three cells
    x_edges, y_edges = np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 10.0, 20.0])
    segments = vibromap_h5.cell_boundary(mask, x_edges, y_edges)
    assert sum(np.abs(s[1] - s[0]).sum() for s in segments) == pytest.approx(2 + 10 + 1 + 10 + 1 + 20)  # perimeter
    assert len(segments) == 6  # runs along one grid line are joined
    for j, i in np.ndindex(mask.shape):
        centre = (0.5 * (x_edges[i] + x_edges[i + 1]), 0.5 * (y_edges[j] + y_edges[j + 1]))
        assert conftest.inside(segments, centre) == mask[j, i], (j, i)
    assert vibromap_h5.cell_boundary(np.zeros((2, 3), bool), x_edges, y_edges) == []


# ---- plot_soft_map ----------------------------------------------------------------------


def test_soft_map_category_counts_equal_the_counts_from_the_datasets(tmp_path):
    path = tmp_path / "soft.h5"
    arrays = make_map.write_soft_map(path)
    expected = expected_counts(arrays)
    assert expected == {"soft": 4, "rigid": 12, "invalid_soft": 2, "invalid": 2, "unstable": 1, "no_impact": 1,
                        "not_periodic": 1, "not_computed": 1}  # fmt: skip
    m, sl, info, fig = soft_figure(path)
    try:
        counts = plot_soft_map.category_counts(plot_soft_map.classify(sl, info))
        P = plot_soft_map
        assert {name: counts[code] for name, code in (("soft", P.SOFT), ("rigid", P.RIGID), ("invalid_soft", P.INVALID_SOFT),
                ("invalid", P.INVALID), ("unstable", P.UNSTABLE), ("no_impact", P.NO_IMPACT),
                ("not_periodic", P.NOT_PERIODIC), ("not_computed", P.NOT_COMPUTED))} == expected  # fmt: skip
        assert counts[P.UNKNOWN_STABILITY] == 0 and sum(counts.values()) == 24
        assert legend_texts(fig) == [
            "soft (k_con <= 10): 4 cells",
            "rigid: periodic with impacts, k_con > 10: 12 cells",
            "Hertz-invalid (z_max/R* > 0.05), would be soft: 2 cells",
            "Hertz-invalid (z_max/R* > 0.05), would not be soft either: 2 cells",
            "unstable periodic orbit: 1 cell",
            "no impact (no contact, permanent contact): 1 cell",
            "not periodic (chatter, chaotic, failed, ...): 1 cell",
            "not computed: 1 cell",
        ]
        title = fig.axes[0].get_title()
        assert "soft = periodic with impacts, stable, Hertz-valid (z_max/R* <= 0.05) and k_con <= 10" in title
        assert SHOOTING_LINE not in title
        [hatched] = [c for c in fig.axes[0].collections if c.get_gid() == "hertz-invalid"]
        assert len(hatched.get_paths()) == 4
    finally:
        matplotlib.pyplot.close(fig)


def test_soft_map_script_writes_a_png_with_each_categorys_colour(tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    result = run([*SCRIPT, str(path)])
    assert result.returncode == 0, result.stderr
    out = tmp_path / "soft_soft.png"
    assert result.stdout == f"plot_soft_map: wrote {out}\n"
    assert png_size(out) == (1350, 1050)
    image = matplotlib.image.imread(out)
    colors = {name: color for name, color, _ in plot_soft_map.CATEGORIES}
    # 24 cells on roughly 1070 x 690 px: one cell is ~30,000 px; the legend adds a few hundred.
    for name, cells in (("soft", 4), ("rigid", 12), ("unstable orbit", 1), ("not computed", 1)):
        assert cells * 20_000 < pixels_near(image, colors[name], tol=0.02) < cells * 40_000, name


def test_soft_map_of_a_3d_map_holds_the_other_axis(tmp_path):
    """The soft pattern repeated over R1 (3 values), /soft 0 where R1 = 2: the slice taken decides."""
    path = tmp_path / "map3d.h5"
    a = make_map.soft_pattern()
    stack = {name: np.repeat(value[:, :, None], 3, axis=2) for name, value in a.items()}
    stack["soft"][:, :, 2] = 0
    axes = make_map.SOFT_AXES + [("R1", np.array([0.5, 1.0, 2.0]), "lin")]
    make_map.write_map(path, axes, stack["regime"], stack["n"], stack["k"], stable=stack["stable"],
                       quantities={"k_con": stack["k_con"]}, soft=stack["soft"], hertz_valid=stack["hertz_valid"],
                       attributes={"soft_kcon": 10.0, "hertz_limit": 0.05, "steady": "follow"})  # fmt: skip
    for r1, soft_cells in ((1.0, 4), (1.9, 0)):
        _, sl, _, fig = soft_figure(path, "E1", "E2", {"R1": r1})
        try:
            assert legend_texts(fig)[0] == f"soft (k_con <= 10): {soft_cells} cell{'s' if soft_cells != 1 else ''}"
            assert sl.fixed_text() == f"R1 = {1 if r1 == 1.0 else 2} m"
        finally:
            matplotlib.pyplot.close(fig)
    out = tmp_path / "r.png"
    result = run([LAUNCHER, "plot_soft_map", str(path), "--x", "E2", "--y", "R1", "--fix", "E1=1e5", "-o", str(out)],
                 VIBROMAP_PYTHON=sys.executable)  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert result.stdout == f"plot_soft_map: wrote {out}\n" and png_size(out) == (1350, 1050)


def test_soft_map_of_a_1d_map_is_a_strip(tmp_path):
    """The column E2 = 1e4 of the soft pattern as a 1-D map over E1: [0] Hertz-invalid (k_con 2),
    [1] soft, [2] rigid, [3] Hertz-invalid (k_con 54), [4], [5] rigid."""
    path = tmp_path / "strip.h5"
    a = {name: value[:, 0] for name, value in make_map.soft_pattern().items()}
    make_map.write_map(path, make_map.SOFT_AXES[:1], a["regime"], a["n"], a["k"], stable=a["stable"],
                       quantities={"k_con": a["k_con"]}, soft=a["soft"], hertz_valid=a["hertz_valid"])  # fmt: skip
    _, sl, _, fig = soft_figure(path)
    try:
        assert sl.y is None and fig.get_size_inches().tolist() == list(plot_soft_map.STRIP_FIGSIZE_IN)
        assert legend_texts(fig)[:4] == ["soft (k_con <= 10): 1 cell", "rigid: periodic with impacts, k_con > 10: 3 cells",
                                         "Hertz-invalid (z_max/R* > 0.05), would be soft: 1 cell",
                                         "Hertz-invalid (z_max/R* > 0.05), would not be soft either: 1 cell"]  # fmt: skip
    finally:
        matplotlib.pyplot.close(fig)
    out = tmp_path / "strip.png"
    result = run([*SCRIPT, str(path), "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert png_size(out) == (1350, 600)


# ---- every map picture of a shooting map says so ------------------------------------------


def test_every_map_picture_of_a_shooting_map_says_so(tmp_path):
    shooting, follow = tmp_path / "shooting.h5", tmp_path / "follow.h5"
    make_map.write_soft_map(shooting, steady="shooting")
    make_map.write_soft_map(follow, steady="follow")
    for path, said in ((shooting, True), (follow, False)):
        m = vibromap_h5.read_map(path)
        info = vibromap_h5.add_soft_cells(m)
        sl = plot_regime_map.choose_slice(m, None, None, {})
        for fig in (plot_regime_map.plot(m, sl), plot_kcon_map.plot(m, sl, info), plot_soft_map.plot(m, sl, info)):
            try:
                assert (SHOOTING_LINE in fig.axes[0].get_title()) == said, path
            finally:
                matplotlib.pyplot.close(fig)


def test_the_census_cell_picture_of_a_shooting_map_says_so(tmp_path):
    path = tmp_path / "census.h5"
    make_map.write_soft_map(path, steady="shooting", census_attractors=np.int64(1))
    with h5py.File(path, "a") as f:  # a one-attractor census in every cell
        for name, value in (("attractors", np.ones((6, 4), np.int32)), ("soft_fraction", np.ones((6, 4))),
                            ("unresolved_fraction", np.zeros((6, 4))), ("unlisted_fraction", np.zeros((6, 4))),
                            ("budget_fraction", np.zeros((6, 4)))):  # fmt: skip
            f.create_dataset(name, data=value)
        for name, value in (("regime", 0), ("n", 1), ("k", 1), ("stable", 1), ("soft", 1), ("from_rest", 1),
                            ("hertz_valid", 1), ("transient", 0), ("k_con", 5.0), ("T_con", 0.17), ("F_max", 1e4),
                            ("z_ratio", 0.01), ("max_floquet", 0.5), ("fraction", 1.0), ("fraction_stderr", 0.0),
                            ("x1", 0.0), ("x2", 0.05), ("v1", 0.0), ("v2", 0.0)):  # fmt: skip
            f.create_dataset(f"attractor_{name}", data=np.full((6, 4, 1), value))
        f["attractor_regime"].attrs["flag_values"] = np.arange(-1, 9, dtype=np.int8)
        f["attractor_regime"].attrs["flag_meanings"] = make_map.REGIME_MEANINGS
    make_map.seal(path)
    m = vibromap_h5.read_map(path)
    fig = plot_census_map.plot_cell(m, (0, 1))
    try:
        assert SHOOTING_LINE in fig.axes[0].get_title()
    finally:
        matplotlib.pyplot.close(fig)
