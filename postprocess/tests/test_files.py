"""vibromap.files.open on one file of each kind the built program writes (real_files.py): the
kind found, the codes decoded to the names their flags give (checked against the raw codes read
with h5py), units and descriptions kept; and a file that cannot be read raises one
DamagedFileError (a ValueError) with the scripts' line, a crash of the reader included."""

from __future__ import annotations

import json
import os
import signal

import h5py
import numpy as np
import pytest

from stamp import set_version
from vibromap import _guard, files


def raw(path, name):
    with h5py.File(path, "r") as f:
        return np.asarray(f[name][()]), dict(f[name].attrs)


def flag_table(attrs) -> dict[int, str]:
    return dict(zip((int(v) for v in np.atleast_1d(attrs["flag_values"])), str(attrs["flag_meanings"]).split()))


@pytest.mark.parametrize("name, kind", [("map", "regime map"), ("refined", "regime map"), ("census", "regime map"),
                                        ("trajectory", "trajectory file"), ("basins", "basins file"),
                                        ("optimise", "optimisation file"), ("branch", "branch file"),
                                        ("orbit", "orbit-diagram file"), ("curves", "curve file"),
                                        ("restitution", "restitution JSON"), ("accuracy", "accuracy CSV")])  # fmt: skip
def test_every_kind_opens_and_is_named(made, name, kind):
    ds = files.open(made[name])
    assert ds.attrs["vibromap_kind"] == kind
    assert files.kind_of(made[name]) == kind


def test_a_map_has_its_status_and_regime_named_from_the_raw_codes(made):
    ds = files.open(made["map"])
    status, attrs = raw(made["map"], "status")
    table = flag_table(attrs)
    assert ds.status_name.values.tolist() == [[table[int(c)] for c in row] for row in status]
    regime, _ = raw(made["map"], "regime")
    n, _ = raw(made["map"], "n")
    k, _ = raw(made["map"], "k")
    expected = [[f"({n[i, j]},{k[i, j]})" if regime[i, j] == 0 else "?" for j in range(regime.shape[1])]
                for i in range(regime.shape[0])]
    assert ds.regime_name.values.tolist() == expected and regime.min() == 0  # Table 2's cells are all periodic
    assert ds.k_con.attrs["units"] == "1" and ds.E2.attrs["units"] == "Pa" and ds.k_con.attrs["description"] == "softness T / T_con of the longest impact"
    np.testing.assert_array_equal(ds.k_con.values, raw(made["map"], "k_con")[0])


def test_an_adaptive_map_names_how_each_point_got_its_values(made):
    ds = files.open(made["refined"])
    computed, attrs = raw(made["refined"], "computed")
    assert flag_table(attrs) == {-1: "not_decided", 0: "inherited", 1: "solved", 2: "audited"}
    assert ds.computed_name.values.tolist() == [[flag_table(attrs)[int(c)] for c in row] for row in computed]
    assert {"solved", "inherited"} <= set(ds.computed_name.values.ravel())


def test_a_census_map_names_each_attractor_and_the_unlisted_ones(made):
    ds = files.open(made["census"])
    regime, _ = raw(made["census"], "attractor_regime")
    n, _ = raw(made["census"], "attractor_n")
    k, _ = raw(made["census"], "attractor_k")
    names = ds.attractor_regime_name.values
    assert names.shape == regime.shape
    for index in np.ndindex(regime.shape):
        expected = f"({n[index]},{k[index]})" if regime[index] == 0 else "not-computed" if regime[index] == -1 else None
        if expected is not None:
            assert names[index] == expected, index
    assert "attractor_fraction" in ds and ds.sizes["attractor"] == 3


def test_basins_name_each_pixel_by_its_attractor(made):
    ds = files.open(made["basins"])
    label, attrs = raw(made["basins"], "label")
    regime, _ = raw(made["basins"], "regime")
    n, _ = raw(made["basins"], "n")
    k, _ = raw(made["basins"], "k")
    table = flag_table(attrs)
    for index in np.ndindex(label.shape):
        a = int(label[index])
        expected = (f"({n[a]},{k[a]})" if regime[a] == 0 else None) if a >= 0 else table[a]
        assert ds.label_name.values[index] == expected
    assert sorted(set(ds.label_name.values.ravel())) == ["(1,1)", "(3,3)"]  # Table 2 is bistable


def test_a_branch_names_its_bifurcations_and_a_curve_file_gathers_its_curves(made):
    ds = files.open(made["branch"])
    assert ds.bifurcation_type_name.dims == ("bifurcation",) and ds.sizes["point"] == len(raw(made["branch"], "param")[0])
    curves = files.open(made["curves"])
    with h5py.File(made["curves"], "r") as f:
        groups = [g for g in f if g.startswith("curve_")]
        kinds = [f[g].attrs["kind"] for g in groups]
        points = sum(f[g]["param"].shape[0] for g in groups)
    assert curves.curve_kind.values.tolist() == [k.decode() if isinstance(k, bytes) else k for k in kinds]
    assert curves.sizes["point"] == points and curves.point_curve.values.max() == len(groups) - 1
    assert curves.attrs["param2"] == "forcing.F0" and "kind" not in curves.attrs


def test_an_optimisation_gathers_its_starts_and_best_points(made):
    ds = files.open(made["optimise"])
    with h5py.File(made["optimise"], "r") as f:
        objective = np.concatenate([f[f"starts/{s}/objective"][()] for s in sorted(f["starts"])])
        best = [f[f"best/{b}/x"][()] for b in sorted(f["best"])]
        regime = np.concatenate([f[f"starts/{s}/regime"][()] for s in sorted(f["starts"])])
    np.testing.assert_array_equal(ds.objective.values, objective)
    np.testing.assert_array_equal(ds.best_x.values, np.stack(best))
    assert set(ds.regime_name.values[regime == 0]) <= {"(1,1)", "(3,3)"} and ds.variable_name.values.tolist() == ["E2"]


def test_a_trajectory_keeps_units_and_descriptions(made):
    ds = files.open(made["trajectory"])
    assert ds.x1.attrs["units"] == "m" and ds.attrs["regime"] == "(1,1)"
    assert all("description" in ds[v].attrs for v in ds.variables)


def test_restitution_json_is_a_table_of_rows(made):
    ds = files.open(made["restitution"])
    rows = json.loads(open(made["restitution"]).read())
    assert ds.law.values.tolist() == [r["law"] for r in rows]
    np.testing.assert_array_equal(ds.e_effective.values, [r["e_effective"] for r in rows])


def test_the_accuracy_csv_is_a_table_of_cases(made):
    """One case a row, the numbers as numbers (an empty cell NaN), the words as words."""
    import csv

    ds = files.open(made["accuracy"])
    with open(made["accuracy"], newline="") as f:
        rows = list(csv.DictReader(f))
    assert ds.sizes["case"] == len(rows) and rows[0]["method"] == "reference"
    assert ds.method.values.tolist() == [r["method"] for r in rows]
    assert ds.k_con.dtype == np.float64
    np.testing.assert_array_equal(ds.k_con.values, [float(r["k_con"]) for r in rows])
    assert ds.rel_err_k_con.values[0] == 0.0 and np.all(ds.rel_err_k_con.values[1:] > 0.0)


# ---- files that cannot be read --------------------------------------------------------------


def test_a_missing_or_foreign_file_raises_one_value_error(tmp_path):
    with pytest.raises(ValueError, match=r"none\.h5: no such file$"):
        files.open(tmp_path / "none.h5")
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f.attrs["title"] = "someone else's"
    with pytest.raises(files.DamagedFileError, match=r"other\.h5: not a file vibromap writes \(its title is 'someone else's'\)"):
        files.open(other)
    text = tmp_path / "notes.txt"
    text.write_text("hello")
    with pytest.raises(files.DamagedFileError, match="neither HDF5"):
        files.open(text)


def test_another_version_and_a_truncated_file_give_the_scripts_line(made, tmp_path):
    old = tmp_path / "old.h5"
    old.write_bytes(open(made["map"], "rb").read())
    set_version(old, 0)
    with pytest.raises(files.DamagedFileError) as error:
        files.open(old)
    assert str(error.value) == (f"{old}: a regime map of format version 0; this vibromap reads version 2 only: make "
                                "the file again with this vibromap")
    cut = tmp_path / "cut.h5"
    cut.write_bytes(open(made["map"], "rb").read()[:-4096])
    with pytest.raises(files.DamagedFileError, match=str(cut)):
        files.open(cut)


def test_a_reader_that_crashes_is_a_damaged_file_and_this_process_lives():
    ok, line = _guard.check_in_child(lambda path: os.kill(os.getpid(), signal.SIGSEGV), "map.h5")
    assert (ok, line) == (False, "map.h5: damaged: reading it crashed the HDF5 library (SIGSEGV); make it again with "
                                 "vibromap --overwrite")
    assert _guard.check_in_child(lambda path: "regime map", "map.h5") == (True, "regime map")
