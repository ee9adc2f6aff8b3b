"""Tests of the map reader (vibromap_h5.read_map, slice2d, regime_labels) and of the map plots
postprocess/plot_regime_map.py and postprocess/plot_kcon_map.py. Map files are written with
h5py by make_map.py in the layout of include/vibromap/io/map_file.hpp, with known patterns:

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
import sys

import h5py
import matplotlib.image
import matplotlib.text
import numpy as np
import pytest

import conftest
from conftest import run, png_size, pixels_near
import make_map
import plot_kcon_map
import plot_regime_map
import vibromap_h5

REGIME_SCRIPT = os.path.join(conftest.POSTPROCESS_DIR, "plot_regime_map.py")
KCON_SCRIPT = os.path.join(conftest.POSTPROCESS_DIR, "plot_kcon_map.py")
SOFT_SCRIPT = os.path.join(conftest.POSTPROCESS_DIR, "plot_soft_map.py")
VMPY = os.path.join(conftest.POSTPROCESS_DIR, "vmpy")
MIN_PNG_BYTES = 15_000  # a coloured map with axes, legend and title at 1350 x 900 px is well above this

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


@pytest.fixture
def map2d(tmp_path):
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


@pytest.fixture
def map3d(tmp_path):
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


@pytest.fixture
def map1d(tmp_path):
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


# ---- the reader ---------------------------------------------------------------------------


def test_read_map_returns_the_arrays_and_attributes_written(map2d):
    path, arrays = map2d
    m = vibromap_h5.read_map(path)
    assert m.axis_names == ["E1", "E2"] and m.shape == (6, 4) and m.ndim == 2
    np.testing.assert_array_equal(m.axes["E1"].values, E1_2D)
    np.testing.assert_array_equal(m.axes["E2"].values, E2_2D)
    assert (m.axes["E1"].scale, m.axes["E1"].units, m.axes["E1"].long_name) == ("log", "Pa", "Young's modulus of body 1")
    assert m.axes["E2"].label() == "E2 (Young's modulus of body 2), Pa"
    np.testing.assert_array_equal(m.data["regime"], arrays["regime"])
    np.testing.assert_array_equal(m.data["done"], (arrays["regime"] != -1).astype(np.uint8))
    np.testing.assert_array_equal(m.data["status"], np.where(arrays["regime"] == -1, -1, arrays["status"]))
    np.testing.assert_array_equal(m.data["n"], np.where(arrays["regime"] == -1, 0, arrays["n"]))
    np.testing.assert_array_equal(m.data["k"], np.where(arrays["regime"] == -1, 0, arrays["k"]))
    # Floats hold NaN where not computed; everything else exactly as written.
    expected = np.where(arrays["regime"] == -1, np.nan, arrays["k_con"])
    np.testing.assert_array_equal(m.data["k_con"], expected)
    np.testing.assert_array_equal(m.data["T_con"], np.where(arrays["regime"] == -1, np.nan, arrays["T_con"]))
    np.testing.assert_array_equal(m.data["periods"], np.where(arrays["regime"] == -1, 0, 300))
    assert m.data["regime"].dtype == np.int8 and m.data["n"].dtype == np.int32 and m.data["periods"].dtype == np.int64
    assert np.isnan(m.data["wall_s"][0, 3]) and m.data["wall_s"][0, 0] == 0.25
    assert m.units["k_con"] == "1" and m.units["T_con"] == "s" and m.units["wall_s"] == "s"
    assert m.stored == ["T_con", "k_con", "periods"]
    assert m.attrs["cells_total"] == 24 and m.attrs["cells_done"] == 22 and m.attrs["complete"] == 0
    assert m.attrs["Conventions"] == "CF-1.8" and m.attrs["ranks"] == 2
    assert m.attrs["scene"].startswith("[system]")
    assert m.regime_meanings[-1] == "not_computed" and m.regime_meanings[3] == "permanent_contact"
    assert m.status_meanings == {-1: "not_computed", 0: "ok", 1: "budget", 2: "failed", 3: "invalid_input"}
    # stable is always there: unknown (-1) everywhere when the writer was not told otherwise.
    assert m.data["stable"].dtype == np.int8 and np.all(m.data["stable"] == -1)
    assert m.stable_meanings == {-1: "unknown", 0: "unstable", 1: "stable"}
    assert "stable" not in m.stored


def test_read_map_exposes_the_stability_and_the_quantities_not_computed(tmp_path):
    regime, n, k, _, _ = pattern_2d()
    periodic = regime == R["periodic"]
    stable = np.where(periodic, make_map.STABLE["stable"], make_map.STABLE["unknown"])
    stable[1, 0] = stable[4, 1] = make_map.STABLE["unstable"]
    multiplier = np.where(periodic, 0.5, np.nan)
    multiplier[1, 0], multiplier[4, 1] = 1.25, 3.0
    path = tmp_path / "stability.h5"
    make_map.write_map(path, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k, stable=stable,
                       quantities={"max_multiplier": multiplier, "lyapunov": np.full(regime.shape, np.nan)})  # fmt: skip
    m = vibromap_h5.read_map(path)
    done = m.data["done"] != 0
    np.testing.assert_array_equal(m.data["stable"], np.where(done, stable, -1))
    assert m.stored == ["max_multiplier", "lyapunov"]
    assert m.units["max_multiplier"] == "1" and m.units["lyapunov"] == "1/s"
    assert m.data["max_multiplier"][4, 1] == 3.0 and m.data["max_multiplier"][0, 0] == 0.5
    # NaN in a cell done: not computed (no periodic orbit); the done mask tells it from not reached.
    assert done[5, 0] and np.isnan(m.data["max_multiplier"][5, 0])
    assert not done[0, 3] and np.isnan(m.data["max_multiplier"][0, 3])
    assert np.all(np.isnan(m.data["lyapunov"]))
    sl = vibromap_h5.slice2d(m, "E1", "E2")
    assert sl.data["stable"][0, 1] == 0 and sl.data["stable"][1, 4] == 0  # (ny, nx): [E2 index, E1 index]


def test_read_map_of_a_map_without_stability_reads_it_unknown(map2d):
    path, _ = map2d
    with h5py.File(path, "a") as f:
        del f["stable"]  # as written before stability was kept
    m = vibromap_h5.read_map(path)
    assert m.data["stable"].shape == (6, 4) and np.all(m.data["stable"] == -1)
    assert m.stable_meanings[0] == "unstable"


def test_read_map_keeps_the_axis_order_of_the_file(map3d):
    m = vibromap_h5.read_map(map3d[0])
    assert m.axis_names == ["E1", "E2", "R1"] and m.shape == (4, 3, 5)
    assert m.axes["R1"].scale == "lin" and m.axes["R1"].units == "m"
    np.testing.assert_array_equal(m.data["k_con"][:3], map3d[1][:3])
    assert np.isnan(m.data["k_con"][3, 2, 4])


def test_regime_labels_and_counts_of_the_2d_pattern(map2d):
    m = vibromap_h5.read_map(map2d[0])
    labels = m.labels()
    assert labels.shape == (6, 4)
    assert labels[0, 0] == "(1,1)" and labels[4, 1] == "(2,1)" and labels[5, 0] == "failed"
    assert labels[2, 2] == "no-contact" and labels[5, 3] == "chatter"
    assert labels[0, 3] == labels[1, 3] == "not-computed"
    counts = vibromap_h5.regime_counts(labels)
    assert counts == COUNTS_2D
    assert list(counts) == list(COUNTS_2D)  # (n,k) first, kinds in flag order, not-computed last


def test_regime_labels_name_every_code():
    codes = np.arange(-1, 9)
    labels = vibromap_h5.regime_labels(codes, np.where(codes == 0, 3, 0), np.where(codes == 0, 2, 0))
    assert labels.tolist() == [
        "not-computed", "(3,2)", "chatter", "no-contact", "permanent-contact",
        "quasi-periodic", "chaotic", "non-periodic", "unresolved", "failed",
    ]  # fmt: skip
    assert vibromap_h5.regime_labels(np.array([42]), 0, 0).tolist() == ["regime-42"]
    # done == 0 wins over the code; n, k are ignored unless the regime is periodic.
    both = vibromap_h5.regime_labels(np.array([0, 1]), np.array([1, 5]), np.array([1, 9]), done=np.array([0, 1]))
    assert both.tolist() == ["not-computed", "chatter"]
    assert vibromap_h5.regime_counts(["(10,1)", "chatter", "(2,3)", "(2,1)", "not-computed", "odd"]) == {
        "(2,1)": 1, "(2,3)": 1, "(10,1)": 1, "chatter": 1, "odd": 1, "not-computed": 1,
    }  # fmt: skip


def test_slice2d_takes_the_requested_slice_and_reports_the_fixed_value(map3d):
    m = vibromap_h5.read_map(map3d[0])
    sl = vibromap_h5.slice2d(m, "E1", "E2", {"R1": 1.2})  # nearest grid value 1.0, index 2
    assert sl.x.name == "E1" and sl.y.name == "E2"
    assert sl.data["k_con"].shape == (3, 4)  # (ny, nx)
    i, j = np.meshgrid(np.arange(4), np.arange(3))
    np.testing.assert_array_equal(sl.data["k_con"], 1.0 + 100 * i + 10 * j + 2)
    assert (set(sl.labels().ravel()) == {"(3,1)"}) and sl.data["n"].max() == 3
    [held] = sl.fixed
    assert (held.name, held.index, held.value, held.units, held.requested) == ("R1", 2, 1.0, "m", 1.2)
    assert sl.fixed_text() == "R1 = 1 m"


def test_slice2d_defaults_to_the_middle_and_orders_rows_by_y(map3d):
    m = vibromap_h5.read_map(map3d[0])
    sl = vibromap_h5.slice2d(m, "R1", "E1")  # E2 not given: middle index 3 // 2 = 1, 1e6 Pa
    assert sl.data["k_con"].shape == (4, 5)
    i, l = np.meshgrid(np.arange(4), np.arange(5), indexing="ij")
    np.testing.assert_array_equal(sl.data["k_con"], 1.0 + 100 * i + 10 * 1 + l)
    assert sl.labels()[0].tolist() == ["(1,1)", "(2,1)", "(3,1)", "(4,1)", "(5,1)"]
    assert [(f.name, f.index, f.value, f.requested) for f in sl.fixed] == [("E2", 1, 1e6, None)]
    assert sl.fixed_text() == "E2 = 1e+06 Pa"


def test_slice2d_strip_and_nearest_value_in_log_space(map3d):
    m = vibromap_h5.read_map(map3d[0])
    # E1 = 4e5: nearest in log10 is 1e6 (0.40 decades) though 1e5 is nearer linearly.
    sl = vibromap_h5.slice2d(m, "E2", None, {"E1": 4e5, "R1": 2.0})
    assert sl.y is None and sl.data["k_con"].shape == (1, 3)
    np.testing.assert_array_equal(sl.data["k_con"][0], 1.0 + 100 * 1 + 10 * np.arange(3) + 4)
    assert sl.fixed_text() == "E1 = 1e+06 Pa, R1 = 2 m"
    # The last cell [3, 2, 4] is the one not computed.
    last = vibromap_h5.slice2d(m, "E2", None, {"E1": 1e8, "R1": 2.0})
    assert last.labels()[0].tolist() == ["(5,1)", "(5,1)", "not-computed"]


@pytest.mark.parametrize(
    "x, y, fixed, message",
    [
        ("Q", "E2", {}, "no axis 'Q' for x (axes: E1, E2, R1)"),
        ("E1", "m2", {}, "no axis 'm2' for y"),
        ("E1", "E1", {}, "cannot be both x and y"),
        ("E1", "E2", {"R2": 1.0}, "no axis 'R2' to fix"),
        ("E1", "E2", {"E2": 1e6}, "'E2' is the y axis and cannot be fixed"),
        ("E1", "E2", {"R1": float("nan")}, "not finite"),
    ],
)
def test_slice2d_rejects_bad_axes(map3d, x, y, fixed, message):
    m = vibromap_h5.read_map(map3d[0])
    with pytest.raises(vibromap_h5.MapSliceError, match=None) as info:
        vibromap_h5.slice2d(m, x, y, fixed)
    assert message in str(info.value) and "\n" not in str(info.value)


def test_cell_edges_are_midpoints_in_log_space_for_log_axes():
    log_axis = vibromap_h5.MapAxis("E1", np.array([1e4, 1e6, 1e8]), "log", "Pa", "")
    np.testing.assert_allclose(vibromap_h5.cell_edges(log_axis), [1e3, 1e5, 1e7, 1e9], rtol=1e-12)
    lin_axis = vibromap_h5.MapAxis("R1", np.array([0.5, 1.0, 2.0]), "lin", "m", "")
    np.testing.assert_allclose(vibromap_h5.cell_edges(lin_axis), [0.25, 0.75, 1.5, 2.5], rtol=1e-15)
    single = vibromap_h5.MapAxis("m2", np.array([310.0]), "lin", "kg", "")
    np.testing.assert_allclose(vibromap_h5.cell_edges(single), [155.0, 465.0])
    single_log = vibromap_h5.MapAxis("E2", np.array([1e6]), "log", "Pa", "")
    np.testing.assert_allclose(vibromap_h5.cell_edges(single_log), [10**5.5, 10**6.5], rtol=1e-12)


def test_parse_fix():
    assert vibromap_h5.parse_fix(["R1=0.5", "m2 = 3.1e2"]) == {"R1": 0.5, "m2": 310.0}
    assert vibromap_h5.parse_fix(None) == {}
    for bad, message in (("R1", "expected NAME=VALUE"), ("R1=soft", "not a number"), ("=2", "expected NAME=VALUE")):
        with pytest.raises(ValueError, match=message):
            vibromap_h5.parse_fix([bad])
    with pytest.raises(ValueError, match="given twice"):
        vibromap_h5.parse_fix(["R1=1", "R1=2"])


def test_read_map_errors_are_one_line(tmp_path, trajectory_file):
    with pytest.raises(vibromap_h5.VibromapFileError, match="no such file"):
        vibromap_h5.read_map(tmp_path / "missing.h5")
    with pytest.raises(vibromap_h5.VibromapFileError, match=r"not a vibromap map file \(no dataset 'done'\)"):
        vibromap_h5.read_map(trajectory_file[0])
    unattached = tmp_path / "unattached.h5"
    regime, n, k, _, _ = pattern_2d()
    make_map.write_map(unattached, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k, attach_scales=False)
    with pytest.raises(vibromap_h5.VibromapFileError, match="no axis attached to dimension 0"):
        vibromap_h5.read_map(unattached)
    ragged = tmp_path / "ragged.h5"
    make_map.write_map(ragged, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k)
    with h5py.File(ragged, "a") as f:
        del f["n"]
        f.create_dataset("n", data=np.zeros((6, 3), dtype=np.int32))
    with pytest.raises(vibromap_h5.VibromapFileError, match=r"dataset 'n' has shape \(6, 3\)"):
        vibromap_h5.read_map(ragged)


@pytest.mark.filterwarnings("ignore:numpy.ndarray size changed:RuntimeWarning")  # Debian's netCDF4 build
def test_make_map_files_read_as_netcdf_with_xarray(map3d):
    """map_file.hpp promises netCDF-4 compatibility: the test helper must keep it too."""
    xarray = pytest.importorskip("xarray")
    try:
        dataset = xarray.open_dataset(map3d[0])
    except ValueError as exc:  # no netCDF engine installed
        pytest.skip(str(exc))
    with dataset:
        assert dataset["k_con"].dims == ("E1", "E2", "R1")
        np.testing.assert_array_equal(dataset["R1"].values, R1_3D)
        assert dataset.attrs["stored"] == "k_con"


@pytest.mark.skipif("VIBROMAP_SAMPLE_MAP" not in os.environ, reason="no map file from the C++ writer (run via ctest)")
def test_reader_reads_the_cpp_writers_map():
    """Layout invariants of map_file.hpp on a file written by src/io/map_file.cpp."""
    m = vibromap_h5.read_map(os.environ["VIBROMAP_SAMPLE_MAP"])
    done = m.data["done"] != 0
    assert m.ndim >= 1 and all(axis.scale in ("lin", "log") and axis.units for axis in m.axes.values())
    assert np.all(m.data["regime"][~done] == -1) and np.all(m.data["status"][~done] == -1)
    assert np.all(m.data["n"][~done] == 0)
    assert np.all(np.isnan(m.data["wall_s"][~done]))
    assert m.attrs["cells_total"] == done.size and m.attrs["cells_done"] == int(done.sum())
    assert m.attrs["complete"] == int(done.all())
    assert all(name in m.data for name in m.stored)
    assert m.regime_meanings == dict(zip(range(-1, 9), make_map.REGIME_MEANINGS.split()))
    assert "not-computed" not in set(m.labels()[done].ravel())


# ---- plot_regime_map ----------------------------------------------------------------------


def test_regime_plot_writes_a_png_with_the_regime_colours(map2d, tmp_path):
    out = tmp_path / "regimes.png"
    result = run([sys.executable, REGIME_SCRIPT, str(map2d[0]), "-o", str(out)])
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
    result = run([sys.executable, REGIME_SCRIPT, str(map3d[0]), "--x", "R1", "--y", "E2", "--fix", "E1=3e6", "-o", str(out)])
    assert result.returncode == 0, result.stderr
    # log10(3e6) = 6.48: nearer 1e6 than 1e7 in log space.
    assert result.stdout.splitlines() == [
        "plot_regime_map: note: E1 = 3e+06 is not a grid value; using E1 = 1e+06 Pa",
        f"plot_regime_map: wrote {out}",
    ]
    assert png_size(out) == (1350, 900)


def test_regime_script_default_output_and_strip(map1d):
    result = run([sys.executable, REGIME_SCRIPT, str(map1d)])
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


# ---- plot_kcon_map ------------------------------------------------------------------------

SOFT_DEFINITION = "soft: stable periodic with impacts, Hertz-valid, k_con <= 10"


def soft_outlines(fig):
    return [c for ax in fig.axes for c in ax.collections if c.get_gid() == plot_kcon_map.SOFT_GID]


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
    result = run([sys.executable, KCON_SCRIPT, str(path), "--threshold", "20", "-o", str(out)])
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        "plot_kcon_map: note: soft cells computed from regime, stable, hertz_valid and k_con "
        "(soft: stable periodic with impacts, Hertz-valid, k_con <= 20)",
        f"plot_kcon_map: wrote {out}",
    ]


def test_kcon_figure_of_a_map_without_hertz_validity_says_soft_is_unknown(map3d, tmp_path):
    _, _, fig = kcon_figure(map3d[0], "E1", "E2", {"R1": 0.1})
    try:
        assert soft_outlines(fig) == []
        assert legend_texts(fig) == [
            "soft cells unknown: the map has no /soft, and no hertz_valid or z_ratio to compute it from",
            "Hertz validity unknown: the map stores neither hertz_valid nor z_ratio",
        ]
        assert any("fixed: R1 = 0.1 m" in t for t in figure_texts(fig))
    finally:
        matplotlib.pyplot.close(fig)
    result = run([sys.executable, KCON_SCRIPT, str(map3d[0]), "-o", str(tmp_path / "old.png")])
    assert result.returncode == 0, result.stderr
    assert "plot_kcon_map: note: soft cells unknown: the map has no /soft" in result.stdout


def test_kcon_figure_of_an_older_map_computes_the_same_outline(tmp_path):
    """Without /soft and /hertz_valid (z_ratio, stable and k_con stored) the outline is the same."""
    new, old = tmp_path / "new.h5", tmp_path / "old.h5"
    make_map.write_soft_map(new)
    make_map.write_soft_map(old, new=False)
    outlines = []
    for path in (new, old):
        _, _, fig = kcon_figure(path)
        try:
            [outline] = soft_outlines(fig)
            outlines.append(sorted(map(tuple, np.concatenate(outline.get_segments()).tolist())))
            assert legend_texts(fig)[:2] == [f"{SOFT_DEFINITION} (outlined): 4 cells", "Hertz-invalid (z_max/R* > 0.05): 4 cells"]
        finally:
            matplotlib.pyplot.close(fig)
    assert outlines[0] == outlines[1]


def test_kcon_strip_outlines_the_soft_cells(map1d, tmp_path):
    """map1d with /soft: the (1,1) cells at E2 = 1e5, 1e6, 1e7 (k_con 1, 3.16, 10) are soft."""
    with h5py.File(map1d, "a") as f:
        soft = f.create_dataset("soft", data=np.array([1, 1, 1, 0, 0, 0, -1], dtype=np.int8))
        soft.dims[0].attach_scale(f["E2"])
        f.attrs["soft_kcon"], f.attrs["hertz_limit"] = 10.0, 0.05
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
    result = run([sys.executable, KCON_SCRIPT, str(map1d), "-o", str(out)])
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
        result = run([sys.executable, script, str(empty), "-o", str(tmp_path / "empty.png")])
        assert result.returncode == 0, result.stderr


def test_kcon_script_writes_a_png(tmp_path):
    path = tmp_path / "soft.h5"
    make_map.write_soft_map(path)
    result = run([sys.executable, KCON_SCRIPT, str(path)])
    assert result.returncode == 0, result.stderr
    out = path.with_name("soft_kcon.png")
    assert result.stdout == f"plot_kcon_map: wrote {out}\n"
    assert png_size(out) == (1350, 975)
    assert out.stat().st_size > MIN_PNG_BYTES
    image = matplotlib.image.imread(out)
    assert pixels_near(image, plot_kcon_map.COLOR_SOFT_OUTLINE, tol=0.05) > 300  # the soft outline
    assert pixels_near(image, plot_kcon_map.COLOR_NOT_COMPUTED, tol=0.01) > 15_000
    assert pixels_near(image, plot_kcon_map.COLOR_NO_CONTACT, tol=0.01) > 15_000


# ---- the map scripts: errors, help, launcher -------------------------------------------------

SCRIPTS = [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map"), (SOFT_SCRIPT, "plot_soft_map")]


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_missing_file_gives_exit_2_and_one_line(tmp_path, script, prog):
    missing = tmp_path / "missing.h5"
    one_line_error(run([sys.executable, script, str(missing)]), prog, str(missing), "no such file")


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_not_a_map_gives_exit_2_and_one_line(trajectory_file, script, prog):
    one_line_error(run([sys.executable, script, str(trajectory_file[0])]), prog, "not a vibromap map file")


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_unknown_axis_gives_exit_2_and_one_line(map3d, tmp_path, script, prog):
    out = tmp_path / "never.png"
    one_line_error(run([sys.executable, script, str(map3d[0]), "--x", "omega2", "-o", str(out)]), prog, "no axis 'omega2'", "E1, E2, R1")
    one_line_error(run([sys.executable, script, str(map3d[0]), "--fix", "m2=310", "-o", str(out)]), prog, "no axis 'm2' to fix")
    assert not out.exists()


def test_map_without_kcon_gives_exit_2_and_one_line(tmp_path):
    path = tmp_path / "no_kcon.h5"
    regime, n, k, _, _ = pattern_2d()
    make_map.write_map(path, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k, quantities={"F_max": np.ones(regime.shape)})
    one_line_error(run([sys.executable, KCON_SCRIPT, str(path)]), "plot_kcon_map", "did not store k_con", "stored: F_max", "[sweep] store")
    assert not path.with_name("no_kcon_kcon.png").exists()


@pytest.mark.parametrize("script", [REGIME_SCRIPT, KCON_SCRIPT, SOFT_SCRIPT])
def test_bad_option_values_give_exit_2(map2d, script):
    result = run([sys.executable, script, str(map2d[0]), "--fix", "E1"])
    assert result.returncode == 2 and "expected NAME=VALUE" in result.stderr
    if script == KCON_SCRIPT:
        result = run([sys.executable, script, str(map2d[0]), "--threshold", "-1"])
        assert result.returncode == 2 and "--threshold must be a positive number" in result.stderr


def test_help_describes_the_options():
    result = run([sys.executable, REGIME_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "NAME=VALUE", "--output", "not-computed", "middle"):
        assert fragment in result.stdout, fragment
    result = run([sys.executable, KCON_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "--threshold", "1000", "rigid", "soft", "soft_kcon", "Hertz-valid"):
        assert fragment in result.stdout, fragment
    result = run([sys.executable, SOFT_SCRIPT, "--help"])
    assert result.returncode == 0
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "--output", "soft_kcon", "hertz_limit", "Hertz-invalid", "rigid"):
        assert fragment in result.stdout, fragment


@pytest.mark.parametrize("script, prog", SCRIPTS)
def test_missing_modules_give_a_one_line_hint_to_use_vmpy(script, prog):
    code = (
        "import sys, runpy; sys.modules['h5py'] = None; "
        f"sys.path.insert(0, {conftest.POSTPROCESS_DIR!r}); sys.argv = ['{prog}.py', 'x.h5']; "
        f"runpy.run_path({script!r}, run_name='__main__')"
    )
    result = run([sys.executable, "-c", code])
    assert result.returncode == 3
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and f"postprocess/vmpy {prog}" in lines[0] and "h5py" in lines[0]


def test_scripts_are_executable_with_the_debian_shebang():
    for script, _ in SCRIPTS:
        assert os.access(script, os.X_OK), script
        with open(script) as f:
            assert f.readline() == "#!/usr/bin/python3\n"


@pytest.mark.parametrize("prog, size", [("plot_regime_map", (1350, 900)), ("plot_kcon_map", (1350, 975))])
def test_vmpy_runs_the_map_scripts(map3d, tmp_path, prog, size):
    out = tmp_path / f"{prog}.png"
    result = run([VMPY, prog, str(map3d[0]), "--fix", "R1=1", "-o", str(out)], VIBROMAP_PYTHON=sys.executable)
    assert result.returncode == 0, result.stderr
    assert png_size(out) == size
    listing = run([VMPY, "--help"])
    assert prog in listing.stdout.split()
