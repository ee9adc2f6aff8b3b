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
    at 0, 1, ... with the laws' names as ticks; k_con's threshold sits between the columns."""
    path = tmp_path / "law.h5"
    laws = ["hertz", "hunt-crossley", "lankarani-nikravesh", "flores", "gonthier"]
    regime = np.zeros((2, 3), dtype=np.int8)
    k_con = np.array([[5.0, 20.0], [5.0, 20.0], [5.0, 20.0]]).T  # law x E2: soft under flores
    make_map.write_map(path, [("law", [3.0, 0.0], "lin"), ("E2", [1e4, 1e6, 1e8], "log")], regime,
                       np.ones((2, 3), dtype=np.int32), np.ones((2, 3), dtype=np.int32),
                       quantities={"k_con": k_con}, categories={"law": laws})
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
    [segment] = plot_kcon_map.threshold_segments(sl, np.ma.masked_invalid(m.data["k_con"].T), 10.0)
    assert len(segment) >= 2
    np.testing.assert_allclose(segment[:, 0], 0.5)  # halfway between the two laws' columns


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


def threshold_lines(fig):
    return [c for ax in fig.axes for c in ax.collections if c.get_gid() == plot_kcon_map.THRESHOLD_GID]


def test_kcon_figure_draws_the_threshold_contour_where_it_crosses(map2d):
    m = vibromap_h5.read_map(map2d[0])
    sl = plot_regime_map.choose_slice(m, None, None, {})
    fig = plot_kcon_map.plot(m, sl, threshold=5.0)
    try:
        [lines] = threshold_lines(fig)
        segments = lines.get_segments()
        assert segments and sum(len(s) for s in segments) >= 2
        points = np.concatenate(segments)
        # k_con = sqrt(E1/1e4) = 5 at E1 = 2.5e5 for every E2 with an impact (rows j = 0, 1).
        np.testing.assert_allclose(points[:, 0], 2.5e5, rtol=1e-12)
        assert points[:, 1].min() == pytest.approx(1e4) and points[:, 1].max() == pytest.approx(1e6)
        ax = fig.axes[0]
        assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
        mesh = [c for c in ax.collections if isinstance(c.norm, matplotlib.colors.LogNorm)]
        assert len(mesh) == 1 and mesh[0].norm.vmin == pytest.approx(10**0.5) and mesh[0].norm.vmax == pytest.approx(1000)
        assert mesh[0].get_array().mask.sum() == 4 + 1 + 2  # no contact, failed (NaN), not computed
        texts = legend_texts(fig)
        assert texts == ["k_con = 5: soft where k_con < 5, rigid above", "no impact / no k_con: 5 cells", "not computed: 2 cells"]
        assert any("~1000 rigid, ~1-10 soft" in t for t in figure_texts(fig))
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_figure_says_when_the_threshold_is_not_crossed(map3d):
    m = vibromap_h5.read_map(map3d[0])
    sl = plot_regime_map.choose_slice(m, "E1", "E2", {"R1": 0.1})
    fig = plot_kcon_map.plot(m, sl, threshold=1e4)
    try:
        assert threshold_lines(fig) == []
        assert legend_texts(fig) == ["k_con = 10000 not crossed: all soft here (1 to 321)"]
        assert any("fixed: R1 = 0.1 m" in t for t in figure_texts(fig))
    finally:
        matplotlib.pyplot.close(fig)
    fig = plot_kcon_map.plot(m, sl, threshold=150.0)  # k_con = 1 + 100 i + 10 j crosses 150
    try:
        [lines] = threshold_lines(fig)
        assert len(lines.get_segments()) >= 1
    finally:
        matplotlib.pyplot.close(fig)


def test_kcon_strip_marks_the_crossing(map1d, tmp_path):
    m = vibromap_h5.read_map(map1d)
    sl = plot_regime_map.choose_slice(m, None, None, {})
    fig = plot_kcon_map.plot(m, sl, threshold=5.0)
    try:
        [lines] = threshold_lines(fig)
        [segment] = lines.get_segments()
        np.testing.assert_allclose(segment[:, 0], 2.5e6, rtol=1e-12)
        np.testing.assert_array_equal(segment[:, 1], [0.0, 1.0])
    finally:
        matplotlib.pyplot.close(fig)
    out = tmp_path / "strip.png"
    result = run([sys.executable, KCON_SCRIPT, str(map1d), "-o", str(out), "--threshold", "5"])
    assert result.returncode == 0, result.stderr
    assert png_size(out) == (1350, 525)


def test_kcon_one_cell_wide_slices_and_a_map_with_nothing_done(tmp_path):
    path = tmp_path / "thin.h5"
    axes = [("m2", np.array([100.0, 200.0, 310.0]), "lin"), ("k2", np.array([4000.0]), "log")]
    make_map.write_map(path, axes, np.zeros((3, 1), int), np.ones((3, 1)), np.ones((3, 1)), quantities={"k_con": np.array([[3.0], [10.0], [30.0]])})
    m = vibromap_h5.read_map(path)
    k2_edges = vibromap_h5.cell_edges(m.axes["k2"])
    # k_con = 10 sits on the grid value m2 = 200: one crossing, not one per neighbouring interval.
    for x, y, expected in (("m2", "k2", [[200.0, k2_edges[0]], [200.0, k2_edges[1]]]),
                           ("k2", "m2", [[k2_edges[0], 200.0], [k2_edges[1], 200.0]])):  # fmt: skip
        fig = plot_kcon_map.plot(m, vibromap_h5.slice2d(m, x, y), threshold=10.0)
        try:
            [lines] = threshold_lines(fig)
            [segment] = lines.get_segments()
            np.testing.assert_allclose(segment, expected, rtol=1e-12)
        finally:
            matplotlib.pyplot.close(fig)

    empty = tmp_path / "empty.h5"
    make_map.write_map(empty, axes, np.full((3, 1), -1), np.zeros((3, 1)), np.zeros((3, 1)), quantities={"k_con": np.ones((3, 1))})
    m = vibromap_h5.read_map(empty)
    assert vibromap_h5.regime_counts(m.labels()) == {"not-computed": 3}
    fig = plot_kcon_map.plot(m, plot_regime_map.choose_slice(m, None, None, {}))
    try:
        assert threshold_lines(fig) == []
        assert legend_texts(fig) == ["no cell with an impact in this slice", "not computed: 3 cells"]
    finally:
        matplotlib.pyplot.close(fig)
    for script in (REGIME_SCRIPT, KCON_SCRIPT):
        result = run([sys.executable, script, str(empty), "-o", str(tmp_path / "empty.png")])
        assert result.returncode == 0, result.stderr


def test_kcon_script_writes_a_png(map2d, tmp_path):
    result = run([sys.executable, KCON_SCRIPT, str(map2d[0])])
    assert result.returncode == 0, result.stderr
    out = map2d[0].with_name("map2d_kcon.png")
    assert result.stdout == f"plot_kcon_map: wrote {out}\n"
    assert png_size(out) == (1350, 975)
    assert out.stat().st_size > MIN_PNG_BYTES
    image = matplotlib.image.imread(out)
    assert pixels_near(image, plot_kcon_map.COLOR_THRESHOLD, tol=0.05) > 300  # the threshold line
    assert pixels_near(image, plot_kcon_map.COLOR_NOT_COMPUTED, tol=0.01) > 2 * 15_000
    assert pixels_near(image, plot_kcon_map.COLOR_NO_IMPACT, tol=0.01) > 5 * 15_000


# ---- both scripts: errors, help, launcher ---------------------------------------------------


@pytest.mark.parametrize("script, prog", [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map")])
def test_missing_file_gives_exit_2_and_one_line(tmp_path, script, prog):
    missing = tmp_path / "missing.h5"
    one_line_error(run([sys.executable, script, str(missing)]), prog, str(missing), "no such file")


@pytest.mark.parametrize("script, prog", [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map")])
def test_not_a_map_gives_exit_2_and_one_line(trajectory_file, script, prog):
    one_line_error(run([sys.executable, script, str(trajectory_file[0])]), prog, "not a vibromap map file")


@pytest.mark.parametrize("script, prog", [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map")])
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


@pytest.mark.parametrize("script", [REGIME_SCRIPT, KCON_SCRIPT])
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
    for fragment in ("MAP.h5", "--x", "--y", "--fix", "--threshold", "1000", "rigid", "soft", "default: 10"):
        assert fragment in result.stdout, fragment


@pytest.mark.parametrize("script, prog", [(REGIME_SCRIPT, "plot_regime_map"), (KCON_SCRIPT, "plot_kcon_map")])
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
    for script in (REGIME_SCRIPT, KCON_SCRIPT):
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
