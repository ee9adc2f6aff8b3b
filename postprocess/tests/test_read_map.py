"""Tests of the map reader: vibromap_h5.read_map, slice2d, regime_labels, cell_edges, parse_fix,
on the map files of map_cases.py (their patterns are described there)."""

from __future__ import annotations

import os

import h5py
import numpy as np
import pytest

import make_map
from map_cases import COUNTS_2D, E1_2D, E2_2D, R, R1_3D, pattern_2d
from vibromap import _io as vibromap_h5


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
    assert m.stored == ["hertz_valid", "T_con", "k_con", "periods"]
    assert m.attrs["cells_total"] == 24 and m.attrs["cells_done"] == 22 and m.attrs["complete"] == 0
    assert m.attrs["Conventions"] == "CF-1.8" and m.attrs["ranks"] == 2
    assert m.attrs["scene"].startswith("[system]")
    assert m.regime_meanings[-1] == "not_computed" and m.regime_meanings[3] == "permanent_contact"
    assert m.status_meanings == {-1: "not_computed", 0: "ok", 1: "budget", 2: "failed", 3: "invalid_input"}
    # stable is always there: unknown (-1) everywhere when the writer was not told otherwise.
    assert m.data["stable"].dtype == np.int8 and np.all(m.data["stable"] == -1)
    assert m.stable_meanings == {-1: "unknown", 0: "unstable", 1: "stable"}
    assert "stable" not in m.stored


def test_read_map_names_every_quantity_the_file_stores_even_one_it_does_not_know(tmp_path):
    """The quantities come from the file (its `stored` attribute, each dataset's units and
    long_name), not from a list in the reader: a name no reader has seen is read like the rest."""
    regime, n, k, _, _ = pattern_2d()
    x1_max = np.full(regime.shape, 0.0125)
    path = tmp_path / "new_quantity.h5"
    make_map.write_map(path, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k,
                       quantities={"x1_max": x1_max, "T_con": np.full(regime.shape, 0.1)},
                       long_names={"x1_max": "largest x1 of the steady cycle", "T_con": "duration of the longest impact"})
    m = vibromap_h5.read_map(path)
    assert m.stored == ["hertz_valid", "x1_max", "T_con"]  # every map stores hertz_valid, first
    assert (m.units["x1_max"], m.long_names["x1_max"]) == ("1", "largest x1 of the steady cycle")
    assert m.long_names["T_con"] == "duration of the longest impact" and m.long_names["n"] == ""
    done = m.data["done"] != 0
    np.testing.assert_array_equal(m.data["x1_max"], np.where(done, 0.0125, np.nan))


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
    assert m.stored == ["hertz_valid", "max_multiplier", "lyapunov"]
    assert m.units["max_multiplier"] == "1" and m.units["lyapunov"] == "1/s"
    assert m.data["max_multiplier"][4, 1] == 3.0 and m.data["max_multiplier"][0, 0] == 0.5
    # NaN in a cell done: not computed (no periodic orbit); the done mask tells it from not reached.
    assert done[5, 0] and np.isnan(m.data["max_multiplier"][5, 0])
    assert not done[0, 3] and np.isnan(m.data["max_multiplier"][0, 3])
    assert np.all(np.isnan(m.data["lyapunov"]))
    sl = vibromap_h5.slice2d(m, "E1", "E2")
    assert sl.data["stable"][0, 1] == 0 and sl.data["stable"][1, 4] == 0  # (ny, nx): [E2 index, E1 index]


@pytest.mark.parametrize("dataset", ["stable", "soft", "hertz_valid"])
def test_a_map_without_a_dataset_every_map_has_is_refused(map2d, dataset):
    """No older layout is read: a map of this format version lacking /stable, /soft or
    /hertz_valid (sealed again, so that it is not refused as damaged) is malformed."""
    path, _ = map2d
    with h5py.File(path, "a") as f:
        del f[dataset]
    make_map.seal(path)
    with pytest.raises(vibromap_h5.VibromapFileError) as error:
        vibromap_h5.read_map(path)
    assert str(error.value) == f"{path}: not a vibromap map file (no dataset '{dataset}')"


@pytest.mark.parametrize("attribute", ["steady", "soft_kcon", "hertz_limit", "census_attractors", "identity"])
def test_a_map_without_a_root_attribute_every_map_has_is_refused(tmp_path, attribute):
    path = tmp_path / "m.h5"
    regime, n, k, _, _ = pattern_2d()
    make_map.write_map(path, [("E1", E1_2D, "log"), ("E2", E2_2D, "log")], regime, n, k, attributes={attribute: None})
    with pytest.raises(vibromap_h5.VibromapFileError) as error:
        vibromap_h5.read_map(path)
    assert str(error.value) == f"{path}: not a vibromap map file (no root attribute '{attribute}')"


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
    log_axis = vibromap_h5.MapAxis("E1", np.array([1e4, 1e6, 1e8]), "log", "Pa", "", "contact.E1")
    np.testing.assert_allclose(vibromap_h5.cell_edges(log_axis), [1e3, 1e5, 1e7, 1e9], rtol=1e-12)
    lin_axis = vibromap_h5.MapAxis("R1", np.array([0.5, 1.0, 2.0]), "lin", "m", "", "contact.R1")
    np.testing.assert_allclose(vibromap_h5.cell_edges(lin_axis), [0.25, 0.75, 1.5, 2.5], rtol=1e-15)
    single = vibromap_h5.MapAxis("m2", np.array([310.0]), "lin", "kg", "", "system.m2")
    np.testing.assert_allclose(vibromap_h5.cell_edges(single), [155.0, 465.0])
    single_log = vibromap_h5.MapAxis("E2", np.array([1e6]), "log", "Pa", "", "contact.E2")
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
    with pytest.raises(vibromap_h5.VibromapFileError, match=r"not a vibromap map file \(no root attribute 'title'\)"):
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
    make_map.seal(ragged)
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
        assert dataset.attrs["stored"] == "hertz_valid k_con"


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
