"""--solved (plot_regime_map and the map pictures that share its options): the points an adaptive
map (sweep.refine > 0) solved, computed == 1, drawn as dots, the audited ones, computed == 2, as
crosses, at exactly those points' coordinates; a map without /computed is a one-line error."""

from __future__ import annotations

import sys

import h5py
import matplotlib.legend
import numpy as np
import pytest

from conftest import run
import make_map
from map_cases import KCON_SCRIPT, REGIME_SCRIPT, SOFT_SCRIPT, one_line_error
from vibromap.plot import _regime_map as plot_regime_map
from vibromap import _io as vibromap_h5

R = make_map.REGIME
# A refined map of 3 x 2 coarse points at L = 2: 9 x 5 fine points, the coarse ones (every 4th)
# solved, a band of level-1 and level-2 points solved where the regime changes, two audited.
E1 = np.geomspace(1e5, 1e9, 9)
E2 = np.linspace(1e6, 2e6, 5)


def refined_map(path, with_computed=True, refine_on="regime"):
    shape = (len(E1), len(E2))
    i, _ = np.indices(shape)
    regime = np.where(i < 5, R["periodic"], R["chatter"])
    n = np.where(regime == R["periodic"], 1, 0)
    k = n.copy()
    soft = np.zeros(shape, dtype=np.int8)
    make_map.write_map(path, [("E1", E1, "log"), ("E2", E2, "lin")], regime, n, k, soft=soft,
                       hertz_valid=np.ones(shape, dtype=np.int64), quantities={"k_con": np.full(shape, 20.0)},
                       attributes={"soft_kcon": 10.0, "hertz_limit": 0.05, "steady": "follow"})  # fmt: skip
    computed = np.zeros(shape, dtype=np.int8)
    computed[::4, ::4] = 1  # the coarse points
    computed[4:7, :] = 1  # the band around the change, refined to level 2
    computed[1, 3] = computed[8, 1] = 2  # audited
    if with_computed:
        with h5py.File(path, "a") as f:
            level = np.where(computed > 0, 0, 2).astype(np.int8)
            for name, values in (("computed", computed), ("level", level)):
                f.create_dataset(name, data=values)
                f[name].dims[0].attach_scale(f["E1"])
                f[name].dims[1].attach_scale(f["E2"])
            f.attrs.update({"refine_levels": np.int64(2), "refine_on": refine_on, "refine_audit_fraction": 0.05,
                            "refine_speckle": np.int64(0), "refine_solved_per_level": np.array([6.0, 0.0, 13.0]),
                            "refine_solved": np.int64(19), "refine_inherited": np.int64(24),
                            "refine_audited": np.int64(2), "refine_mismatches": np.int64(0),
                            "refine_mismatch_bound": 0.78, "refine_whole_blocks": np.int64(0)})
        make_map.seal(path)
    return computed


def drawn(fig, gid):
    [points] = [c for c in fig.axes[0].collections if c.get_gid() == gid]
    return sorted(map(tuple, np.asarray(points.get_offsets()).tolist())), points.get_label()


def expected(computed, code):
    rows, cols = np.nonzero(computed == code)
    return sorted(zip(E1[rows].tolist(), E2[cols].tolist()))


def test_an_adaptive_map_says_in_its_title_how_much_was_solved(tmp_path):
    path = tmp_path / "refined.h5"
    computed = refined_map(path, refine_on="soft hertz_valid")
    sweep = vibromap_h5.read_map(str(path))
    solved = int(np.count_nonzero(computed == 1))
    assert solved + 2 == 9 * 5 - int(np.count_nonzero(computed == 0))
    assert sweep.refine_note() == (f"adaptive: {solved} of 45 points solved ({100.0 * solved / 45:.3g} %), "
                                   "2 audited,\nrefined where soft, hertz_valid change; the rest inherited")
    sl = plot_regime_map.choose_slice(sweep, "E1", "E2", {})
    assert plot_regime_map.slice_title("regimes", sweep, sl).splitlines()[-2:] == sweep.refine_note().splitlines()


def test_solved_draws_the_solved_and_audited_points_of_the_map(tmp_path):
    path = tmp_path / "refined.h5"
    computed = refined_map(path)
    sweep = vibromap_h5.read_map(str(path))
    sl = plot_regime_map.choose_slice(sweep, "E1", "E2", {})
    fig = plot_regime_map.plot(sweep, sl)
    plot_regime_map.mark_solved(fig, sweep, sl)
    solved, solved_label = drawn(fig, plot_regime_map.SOLVED_GID)
    audited, audited_label = drawn(fig, plot_regime_map.AUDITED_GID)
    assert solved == expected(computed, 1) and len(solved) == 6 + 15 - 2  # coarse, 3 rows of 5 (2 of them coarse)
    assert audited == expected(computed, 2) == [(E1[1], E2[3]), (E1[8], E2[1])]
    assert solved_label == "solved: 19 points"
    assert audited_label == "audited: 2 points"
    # The regime legend stays, beside the markers' own.
    legends = [a for a in fig.axes[0].get_children() if isinstance(a, matplotlib.legend.Legend)]
    assert sorted(lg.get_title().get_text() for lg in legends) == ["adaptive map", "regime"]


def test_solved_on_transposed_axes_draws_the_same_points(tmp_path):
    path = tmp_path / "refined.h5"
    computed = refined_map(path)
    sweep = vibromap_h5.read_map(str(path))
    sl = plot_regime_map.choose_slice(sweep, "E2", "E1", {})
    fig = plot_regime_map.plot(sweep, sl)
    plot_regime_map.mark_solved(fig, sweep, sl)
    solved, _ = drawn(fig, plot_regime_map.SOLVED_GID)
    assert solved == sorted((y, x) for x, y in expected(computed, 1))


@pytest.mark.parametrize("script", [REGIME_SCRIPT, KCON_SCRIPT, SOFT_SCRIPT])
def test_scripts_take_solved(tmp_path, script):
    path = tmp_path / "refined.h5"
    refined_map(path)
    out = tmp_path / "solved.png"
    result = run([*script, str(path), "--solved", "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert out.stat().st_size > 1000


@pytest.mark.parametrize("script, prog", [(REGIME_SCRIPT, "plot_regime_map"), (SOFT_SCRIPT, "plot_soft_map")])
def test_solved_on_a_uniform_map_is_a_one_line_error(tmp_path, script, prog):
    path = tmp_path / "uniform.h5"
    refined_map(path, with_computed=False)
    out = tmp_path / "never.png"
    one_line_error(run([*script, str(path), "--solved", "-o", str(out)]), prog,
                   str(path), "no dataset 'computed'", "sweep.refine > 0")  # fmt: skip
    assert not out.exists()
