"""Every map's `soft` dataset is the one definition of soft (core/analysis/point/regime.hpp is_soft)
applied to the map's own regime, stability, Hertz validity and k_con; the map says what its
answers mean (root attributes steady, hertz_limit, soft_kcon)."""
import pathlib
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from campaign_helpers import ENV, EXE, MPIEXEC  # noqa: E402

PERIODIC = 0  # regime code of periodic (n,k) motion


def sweep(scene_sets, out, ranks=2):
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "sweep", "jobs/demo/e1_e2.toml", "-o", str(out), "--overwrite",
           "--format", "json", *[a for s in scene_sets for a in ("--set", s)]]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def expected_soft(f):
    """The definition applied to the map's datasets."""
    regime, k, stable = f["regime"][()], f["k"][()], f["stable"][()]
    valid, k_con = f["hertz_valid"][()], f["k_con"][()]
    assert np.array_equal(valid, (f["z_ratio"][()] <= f.attrs["hertz_limit"]).astype(valid.dtype))
    with np.errstate(invalid="ignore"):
        small = (k_con > 0) & (k_con <= f.attrs["soft_kcon"])
    return ((regime == PERIODIC) & (k > 0) & (stable == 1) & (valid == 1) & small).astype(np.int8)


def test_the_soft_dataset_is_the_definition_applied_to_the_map(tmp_path):
    out = tmp_path / "plane.h5"
    # A coarse copy of the demo plane: soft cells, rigid cells and Hertz-invalid cells with small k_con.
    report = sweep(['sweep.E1={from=1e5,to=2.1e11,n=7,scale="log"}', 'sweep.E2={from=2e4,to=1e9,n=6,scale="log"}'],
                   out)
    with h5py.File(out, "r") as f:
        soft = f["soft"][()]
        assert f.attrs["steady"] == "follow" or f.attrs["steady"] == b"follow"
        np.testing.assert_array_equal(soft, expected_soft(f))
        invalid_small = (f["hertz_valid"][()] == 0) & (f["k_con"][()] <= f.attrs["soft_kcon"])
        assert soft.sum() >= 3, "the plane should hold soft cells"
        assert invalid_small.sum() >= 3, "the plane should hold Hertz-invalid cells with small k_con"
        assert not (soft.astype(bool) & invalid_small).any()
        assert f["soft"].attrs["flag_meanings"] in ("not_computed no yes", b"not_computed no yes")
    assert f'"soft_cells": {int(soft.sum())}' in report


def test_a_soft_kcon_key_moves_the_threshold_and_the_flag(tmp_path):
    out = tmp_path / "plane.h5"
    sweep(['sweep.E1={from=1e9,to=2.1e11,n=3,scale="log"}', 'sweep.E2={from=1e5,to=1e7,n=3,scale="log"}',
           "analysis.soft_kcon=30"], out, ranks=1)
    with h5py.File(out, "r") as f:
        assert f.attrs["soft_kcon"] == 30.0
        np.testing.assert_array_equal(f["soft"][()], expected_soft(f))
