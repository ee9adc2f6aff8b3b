"""Tests of the regime-map file written by the C++ writer (src/io/map_file.cpp), read the way
users read it: with h5py, and with xarray through both netCDF-4 engines (netcdf4 and h5netcdf).

ctest writes the file first (tests/io/test_map_file.cpp, MapFileSample) and names it in
VIBROMAP_SAMPLE_MAP; without it (pytest run by hand) these tests are skipped. The sample is a
3 x 4 map over E1 (log) and R1 (lin) whose cell i (flat, row-major, E1 slowest) follows the
formulas below: keep them equal to sample_cell / sample_done in tests/io/test_map_file.cpp."""

from __future__ import annotations

import os

import h5py
import numpy as np
import pytest

E1 = np.array([2e4, 1e7, 2.1e11])  # Pa
R1 = np.array([0.09, 0.5, 1.0, 2.0])  # m
SHAPE = (3, 4)
STORED = ["T_con", "k_con", "hertz_valid", "periods", "max_multiplier", "lyapunov"]
NOT_STORED = ["F_max", "z_max", "z_ratio", "v_in", "impulse", "rhs_evals"]
REGIME_MEANINGS = ("not_computed periodic chatter no_contact permanent_contact quasi_periodic chaotic "
                   "non_periodic unresolved failed")
STATUS_MEANINGS = "not_computed ok budget failed invalid_input"
STABLE_MEANINGS = "unknown unstable stable"
N_DIM = ["done", "status", "regime", "stable", "soft", "n", "k", "wall_s", "steady_residual"] + STORED
DTYPES = {"done": "u1", "status": "i1", "regime": "i1", "stable": "i1", "soft": "i1", "n": "i4", "k": "i4", "wall_s": "f8",
          "steady_residual": "f8", "T_con": "f8", "k_con": "f8", "hertz_valid": "i8", "periods": "i8",
          "max_multiplier": "f8", "lyapunov": "f8"}
FLOATS = ["wall_s", "steady_residual", "T_con", "k_con", "max_multiplier", "lyapunov"]

i = np.arange(SHAPE[0] * SHAPE[1])
DONE = i % 5 != 3  # cells 3 and 8 not computed yet
# Stability unknown / unstable / stable in turn: no multiplier where unknown (NaN in a cell
# done: not computed), > 1 where unstable; the Lyapunov exponent only in odd cells.
STABLE = i % 3 - 1
MULTIPLIER = np.where(i % 3 == 0, np.nan, np.where(i % 3 == 1, 1.0 + 0.25 * (i + 1.0), 1.0 / (i + 2.0)))
LYAPUNOV = np.where(i % 2 == 0, np.nan, (i + 1.0) / 64.0 - 0.0625)


def expected(values: np.ndarray, fill) -> np.ndarray:
    """The formula's values on the grid, `fill` where the cell is not done."""
    return np.where(DONE, values, fill).reshape(SHAPE)


EXPECTED = {
    "done": expected(np.ones_like(i), 0),
    "status": expected(i % 4, -1),
    "regime": expected(i % 9, -1),
    "n": expected(1 + i % 3, 0),
    "k": expected(1 + i % 2, 0),
    "hertz_valid": expected(i % 2, 0),
    "periods": expected(100 + 10 * i, 0),
    # The same IEEE operations as the C++ formulas, so equal to the last bit.
    "wall_s": expected(0.25 * (i + 1.0), np.nan),
    "steady_residual": expected(1e-9 * (i + 1.0), np.nan),
    "T_con": expected(1e-3 * (i + 1.0), np.nan),
    "k_con": expected(1000.0 / (i + 1.0), np.nan),
    "stable": expected(STABLE, -1),
    "max_multiplier": expected(MULTIPLIER, np.nan),
    "lyapunov": expected(LYAPUNOV, np.nan),
}


@pytest.fixture(scope="module")
def sample_map():
    path = os.environ.get("VIBROMAP_SAMPLE_MAP")
    if path is None:
        pytest.skip("no map file from the C++ writer (VIBROMAP_SAMPLE_MAP is set by ctest)")
    return path


# ---- h5py -------------------------------------------------------------------------------


def test_h5py_sees_the_axes_as_dimension_scales(sample_map):
    with h5py.File(sample_map, "r") as f:
        for name, values, units, scale in (("E1", E1, "Pa", "log"), ("R1", R1, "m", "lin")):
            axis = f[name]
            assert h5py.h5ds.is_scale(axis.id)
            assert axis.attrs["NAME"] == name.encode()  # the dimension name netCDF reads
            assert axis.dtype == np.float64
            np.testing.assert_array_equal(axis[()], values)
            assert axis.attrs["units"] == units
            assert axis.attrs["scale"] == scale
            assert axis.attrs["long_name"]
        for name in N_DIM:
            ds = f[name]
            assert ds.shape == SHAPE, name
            assert [d.keys() for d in ds.dims] == [["E1"], ["R1"]], name
            assert [d[0].name for d in ds.dims] == ["/E1", "/R1"], name


def test_h5py_reads_the_cells_and_their_fill_values(sample_map):
    with h5py.File(sample_map, "r") as f:
        for name, values in EXPECTED.items():
            assert f[name].dtype == np.dtype(DTYPES[name]), name
            np.testing.assert_array_equal(f[name][()], values, err_msg=name)
        for name in FLOATS:
            fill = f[name].attrs["_FillValue"]
            assert fill.dtype == f[name].dtype and np.isnan(fill), name  # of the dataset's own type
            assert np.isnan(f[name].fillvalue), name
        for name in NOT_STORED:
            assert name not in f, name


def test_h5py_reads_the_flags_and_root_attributes(sample_map):
    with h5py.File(sample_map, "r") as f:
        regime, status = f["regime"].attrs, f["status"].attrs
        assert regime["flag_values"].dtype == np.int8  # the data's type, as CF asks
        np.testing.assert_array_equal(regime["flag_values"], np.arange(-1, 9))
        assert regime["flag_meanings"] == REGIME_MEANINGS
        assert status["flag_values"].dtype == np.int8
        np.testing.assert_array_equal(status["flag_values"], np.arange(-1, 4))
        assert status["flag_meanings"] == STATUS_MEANINGS
        stable = f["stable"].attrs
        assert stable["flag_values"].dtype == np.int8
        np.testing.assert_array_equal(stable["flag_values"], [-1, 0, 1])
        assert stable["flag_meanings"] == STABLE_MEANINGS
        assert "stability" in stable["long_name"]
        soft = f["soft"].attrs
        np.testing.assert_array_equal(soft["flag_values"], [-1, 0, 1])
        assert soft["flag_meanings"] == "not_computed no yes"
        assert "Hertz-valid" in soft["long_name"]
        assert "NaN where not computed" in f["max_multiplier"].attrs["long_name"]
        assert f["lyapunov"].attrs["units"] == "1/s"
        root = f.attrs
        assert root["Conventions"] == "CF-1.8"
        assert root["title"] == "vibromap regime map"
        assert (root["cells_total"], root["cells_done"], root["complete"], root["ranks"]) == (12, 10, 0, 3)
        assert root["stored"].split() == STORED
        assert "\u03bb" in root["scene"]


# ---- xarray, both netCDF-4 engines --------------------------------------------------------


@pytest.fixture(params=["netcdf4", "h5netcdf"])
def dataset(request, sample_map):
    """The sample opened with xarray; an engine is skipped only when its module is missing."""
    xr = pytest.importorskip("xarray")
    pytest.importorskip({"netcdf4": "netCDF4", "h5netcdf": "h5netcdf"}[request.param])
    with xr.open_dataset(sample_map, engine=request.param) as ds:
        ds.load()
        yield ds


def test_xarray_names_the_dims_after_the_axes(dataset):
    assert dict(dataset.sizes) == {"E1": 3, "R1": 4}
    np.testing.assert_array_equal(dataset["E1"].values, E1)
    np.testing.assert_array_equal(dataset["R1"].values, R1)
    assert list(dataset.coords) == ["E1", "R1"]
    assert dataset["E1"].attrs["units"] == "Pa"
    for name in N_DIM:
        assert dataset[name].dims == ("E1", "R1"), name
    assert set(dataset.data_vars) == set(N_DIM)
    assert list(dataset.data_vars) == N_DIM  # in the order written (creation order tracked)


def test_xarray_decodes_the_regime_with_its_flags(dataset):
    regime = dataset["regime"]
    assert regime.dtype == np.int8  # no _FillValue: the codes stay integers, -1 included
    np.testing.assert_array_equal(regime.values, EXPECTED["regime"])
    np.testing.assert_array_equal(regime.attrs["flag_values"], np.arange(-1, 9))
    assert regime.attrs["flag_values"].dtype == np.int8
    assert regime.attrs["flag_meanings"] == REGIME_MEANINGS
    meanings = regime.attrs["flag_meanings"].split()
    # Cell (E1 = 1e7, R1 = 1.0) is flat index 6: regime code 6 % 9 = 6, RegimeKind::non_periodic.
    code = int(regime.sel(E1=1e7, R1=1.0))
    assert meanings[list(regime.attrs["flag_values"]).index(code)] == "non_periodic"
    assert dataset["status"].attrs["flag_meanings"] == STATUS_MEANINGS


def test_xarray_reads_the_cell_values_and_masks_cells_not_done(dataset):
    for name, values in EXPECTED.items():
        np.testing.assert_array_equal(dataset[name].values, values, err_msg=name)
    t_con = dataset["T_con"]
    assert t_con.attrs["units"] == "s"
    assert np.isnan(t_con.encoding["_FillValue"])
    np.testing.assert_array_equal(t_con.isnull().values, ~DONE.reshape(SHAPE))
    assert float(t_con.sel(E1=2.1e11, R1=2.0)) == 1e-3 * 12.0  # last cell, i = 11
    assert float(dataset["k_con"].sel(E1=2e4, R1=0.5)) == 1000.0 / 2.0  # i = 1
    assert int(dataset["periods"].sel(E1=1e7, R1=0.09)) == 140  # i = 4
    assert dataset.attrs["Conventions"] == "CF-1.8"
    assert int(dataset.attrs["cells_done"]) == 10


def test_xarray_decodes_the_stability_with_its_flags(dataset):
    stable = dataset["stable"]
    assert stable.dtype == np.int8  # no _FillValue: -1 (unknown) stays an integer code
    np.testing.assert_array_equal(stable.values, EXPECTED["stable"])
    np.testing.assert_array_equal(stable.attrs["flag_values"], [-1, 0, 1])
    assert stable.attrs["flag_values"].dtype == np.int8
    meanings = dict(zip(stable.attrs["flag_values"].tolist(), stable.attrs["flag_meanings"].split()))
    assert meanings == {-1: "unknown", 0: "unstable", 1: "stable"}
    assert meanings[int(stable.sel(E1=2e4, R1=0.5))] == "unstable"  # i = 1
    assert meanings[int(stable.sel(E1=2e4, R1=1.0))] == "stable"  # i = 2


def test_xarray_tells_not_computed_from_not_done_by_the_done_mask(dataset):
    multiplier = dataset["max_multiplier"]
    assert multiplier.attrs["units"] == "1"
    assert np.isnan(multiplier.encoding["_FillValue"])
    nan = multiplier.isnull().values
    done = dataset["done"].values == 1
    np.testing.assert_array_equal(nan, ~done | np.isnan(MULTIPLIER).reshape(SHAPE))
    assert nan[0, 0] and done[0, 0]  # i = 0: done, no multiplier computed
    assert nan[0, 3] and not done[0, 3]  # i = 3: not done
    assert float(multiplier.sel(E1=2e4, R1=0.5)) == 1.5  # i = 1, unstable
    assert float(dataset["lyapunov"].sel(E1=2.1e11, R1=2.0)) == 0.125  # i = 11
    assert dataset["lyapunov"].attrs["units"] == "1/s"
