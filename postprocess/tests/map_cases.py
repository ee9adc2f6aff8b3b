"""The map files of the map tests (test_read_map.py, test_plot_maps.py, test_plot_kcon_map.py),
written with h5py by make_map.py in the layout of include/vibromap/io/map_file.hpp with known
patterns (conftest.py's fixtures map1d, map2d, map3d write them into the test's folder), and the
helpers these tests share:

  2-D map, E1 (log, 1e5..1e10, 6 points) x E2 (log, 1e4..1e10, 4 points), cell [i, j]:
      i < 3, j < 2: (1,1)          i >= 3, j < 2: (2,1), but [5, 0] failed
      i < 3, j >= 2: no contact,   but [0, 3] and [1, 3] not computed
      i >= 3, j >= 2: chatter
      k_con = sqrt(E1 / 1e4) (3.16 .. 1000) where periodic or chatter, 0 without contact, NaN
      where failed: k_con = 5 is crossed at E1 = 1e4 * 5^2 = 2.5e5 exactly (log interpolation)
  3-D map, E1 (log, 1e5..1e8) x E2 (log, 1e4, 1e6, 1e8) x R1 (lin, 0.1 .. 2), cell [i, j, l]:
      regime (l+1, 1), k_con = 1 + 100 i + 10 j + l (so a slice shows which cells it took)
"""

from __future__ import annotations

import os

import matplotlib.text
import numpy as np

import conftest
import make_map
from vibromap.plot import _kcon_map as plot_kcon_map

POSTPROCESS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REGIME_SCRIPT = conftest.script("plot_regime_map")
KCON_SCRIPT = conftest.script("plot_kcon_map")
SOFT_SCRIPT = conftest.script("plot_soft_map")
LAUNCHER = conftest.LAUNCHER
MIN_PNG_BYTES = 15_000  # a coloured map with axes, legend and title at 1350 x 900 px is well above this
SOFT_DEFINITION = "soft: stable periodic with impacts, Hertz-valid, k_con <= 10"  # the legend entry of soft_outlines

E1_2D = np.geomspace(1e5, 1e10, 6)
E2_2D = np.array([1e4, 1e6, 1e8, 1e10])
COUNTS_2D = {"(1,1)": 6, "(2,1)": 5, "chatter": 6, "no-contact": 4, "failed": 1, "not-computed": 2}
E1_3D = np.array([1e5, 1e6, 1e7, 1e8])
E2_3D = np.array([1e4, 1e6, 1e8])
R1_3D = np.array([0.1, 0.5, 1.0, 1.5, 2.0])
R = make_map.REGIME


def pattern_2d():
    shape = (len(E1_2D), len(E2_2D))
    i, j = np.indices(shape)
    regime = np.select(
        [(i < 3) & (j < 2), (i >= 3) & (j < 2), (i < 3) & (j >= 2)],
        [R["periodic"], R["periodic"], R["no_contact"]],
        R["chatter"],
    )
    n = np.where(regime == R["periodic"], np.where(i < 3, 1, 2), 0)
    k = np.where(regime == R["periodic"], 1, 0)
    regime[5, 0], n[5, 0], k[5, 0] = R["failed"], 0, 0
    regime[0, 3] = regime[1, 3] = R["not_computed"]
    k_con = np.sqrt(E1_2D[:, None] / 1e4) * np.ones(shape)
    k_con = np.where(regime == R["no_contact"], 0.0, k_con)
    k_con[5, 0] = np.nan
    status = np.where(regime == R["failed"], make_map.STATUS["failed"], make_map.STATUS["ok"])
    return regime, n, k, k_con, status


def write_map2d(tmp_path):
    """(path, arrays) of the 2-D map described in the module docstring, with k_con and T_con."""
    regime, n, k, k_con, status = pattern_2d()
    t_con = np.where(k_con > 0, 0.869 / np.where(k_con > 0, k_con, 1.0), 0.0)
    periods = np.full(regime.shape, 300)
    path = tmp_path / "map2d.h5"
    make_map.write_map(
        path,
        [("E1", E1_2D, "log"), ("E2", E2_2D, "log")],
        regime,
        n,
        k,
        status=status,
        quantities={"T_con": t_con, "k_con": k_con, "periods": periods},
    )
    return path, dict(regime=regime, n=n, k=k, k_con=k_con, T_con=t_con, periods=periods, status=status)


def write_map3d(tmp_path):
    """(path, k_con) of the 3-D map described in the module docstring; cell [3, 2, 4] not done."""
    i, j, l = np.indices((len(E1_3D), len(E2_3D), len(R1_3D)))
    regime = np.full(i.shape, R["periodic"])
    regime[3, 2, 4] = R["not_computed"]
    k_con = 1.0 + 100 * i + 10 * j + l
    path = tmp_path / "map3d.h5"
    make_map.write_map(
        path,
        [("E1", E1_3D, "log"), ("E2", E2_3D, "log"), ("R1", R1_3D, "lin")],
        regime,
        l + 1,
        np.ones(i.shape, dtype=int),
        quantities={"k_con": k_con},
    )
    return path, k_con


def write_map1d(tmp_path):
    """A 1-D map over E2 (log, 1e5..1e11, 7 points): k_con = 10^(i/2) (1 .. 1000), crossing 5 at
    E2 = 10^(5 + 2 log10 5) = 2.5e6; cells (1,1) x3, chatter x2, no contact, not computed."""
    e2 = np.geomspace(1e5, 1e11, 7)
    regime = np.array([0, 0, 0, 1, 1, 2, -1])
    k_con = 10.0 ** (np.arange(7) / 2.0)
    k_con[5] = 0.0
    path = tmp_path / "map1d.h5"
    make_map.write_map(
        path, [("E2", e2, "log")], regime, np.where(regime == 0, 1, 0), np.where(regime == 0, 1, 0), quantities={"k_con": k_con}
    )
    return path


def figure_texts(fig) -> list[str]:
    """Every non-empty text on the figure: titles, labels, tick labels, legend entries."""
    return [t.get_text() for t in fig.findobj(matplotlib.text.Text) if t.get_text()]


def legend_texts(fig) -> list[str]:
    return [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]


def one_line_error(result, prog, *fragments):
    assert result.returncode == 2, (result.returncode, result.stderr)
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"{prog}: error: ")
    for fragment in fragments:
        assert fragment in lines[0], lines[0]


def soft_outlines(fig):
    return [c for ax in fig.axes for c in ax.collections if c.get_gid() == plot_kcon_map.SOFT_GID]
