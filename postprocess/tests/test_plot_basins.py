"""Tests of the basins reader (vibromap_h5.read_basins) and postprocess/plot_basins.py, on a file
written here in the layout of include/vibromap/io/basins_file.hpp (stamped: stamp.py) with known
contents:

  x1 (6 points) x v1 (4 points); attractor 0 a soft (1,1) with k_con 8.96 on the left half,
  attractor 1 a (3,3) with k_con 2.5 on the right half, one pixel unresolved, one overlapping;
  with entropy=True, the basin entropy's root attributes as vibromap writes them (made-up
  values: the reader's and the title's job is to carry them, basin_entropy.hpp computes them).
"""
import os

import h5py
import matplotlib.text
import numpy as np

import conftest
from conftest import png_size, run
from vibromap.plot import _basins as plot_basins
from stamp import stamp
from vibromap._io import read_basins

SCRIPT = conftest.script("plot_basins")
SCENE = "[system]\nm2 = 310.0\nomega2 = 3.606\n\n[contact]\nE1 = 1.4e10\nE2 = 1.0e6\n"


# Root attributes of the basin entropy (include/vibromap/io/basins_file.hpp).
ENTROPY = {"entropy_box": np.int64(2), "entropy_boxes": np.int64(6), "entropy_boundary_boxes": np.int64(2),
           "basin_entropy": 0.2, "boundary_basin_entropy": 0.6, "log2_test": "not_shown",
           "uncertainty_fraction": np.array([0.3]), "uncertainty_exponent": np.nan, "boundary_dimension": np.nan,
           "uncertainty_fit_rms": np.nan, "uncertainty_fit_eps_lo": np.int64(0), "uncertainty_fit_eps_hi": np.int64(0),
           "uncertainty_fit_scales": np.int64(0), "uncertainty_note": "1 of the 1 scales ...; the fit needs 3"}


def basins_file(path, entropy=False):
    x1, v1 = np.linspace(-0.05, 0.05, 6), np.linspace(-0.36, 0.36, 4)
    label = np.where(np.arange(6)[None, :] < 3, 0, 1).repeat(4, axis=0).astype(np.int32)
    label[0, 0] = -1
    label[3, 5] = -3
    with h5py.File(path, "w") as f:
        f.attrs.update({"vibromap_version": "0.1.0", "plane": "x1,v1", "fixed": "x2=0.05 v2=0", "complete": 1, "attractors": 2, "scene": SCENE,
                        "fixed_state": np.array([0.0, 0.05, 0.0, 0.0])})
        for name, values, units in (("x1", x1, "m"), ("v1", v1, "m/s")):
            f[name] = values
            f[name].attrs["units"] = units
        f["label"] = label
        f["done"] = np.ones_like(label, dtype=np.uint8)
        f["regime"] = np.array([0, 0], np.int8)
        f["regime"].attrs["flag_values"] = np.arange(9, dtype=np.int8)
        f["regime"].attrs["flag_meanings"] = ("periodic chatter permanent_contact no_contact non_periodic unresolved "
                                              "unbounded failed other")
        f["n"], f["k"] = np.array([1, 3], np.int32), np.array([1, 3], np.int32)
        f["k_con"], f["T_con"], f["F_max"] = np.array([8.96, 2.5]), np.array([0.097, 0.35]), np.array([1e4, 2e4])
        f["stable"], f["soft"] = np.array([1, 1], np.int8), np.array([1, 0], np.uint8)
        f["pixels"] = np.array([11, 11])
        f["fraction"] = np.array([0.523, 0.477])
        f["strobe_points"] = np.array([1, 3], np.int32)
        strobe = np.full((2, 3, 4), np.nan)
        strobe[0, 0] = [0.01, 0.05, 0.1, 0.0]
        strobe[1] = [[0.02, 0.05, 0.1, 0.0]] * 3
        f["strobe"] = strobe
        if entropy:
            f.attrs.update(ENTROPY)
    stamp(path, "basins file")
    return path


def test_reader(tmp_path):
    b = read_basins(basins_file(tmp_path / "b.h5"))
    assert (b.x_name, b.y_name, b.x_units, b.y_units) == ("x1", "v1", "m", "m/s")
    assert b.label.shape == (4, 6)
    assert [a.regime for a in b.attractors] == ["(1,1)", "(3,3)"]
    assert b.attractors[1].strobe.shape == (3, 4)


def test_reader_of_the_basin_entropy(tmp_path):
    assert read_basins(basins_file(tmp_path / "old.h5")).entropy is None  # a file made before vibromap wrote it
    e = read_basins(basins_file(tmp_path / "b.h5", entropy=True)).entropy
    assert (e.box, e.boxes, e.boundary_boxes, e.S_b, e.S_bb, e.log2_test) == (2, 6, 2, 0.2, 0.6, "not_shown")
    assert e.uncertain.tolist() == [0.3] and np.isnan(e.alpha) and e.fit_eps == (0, 0)
    assert e.note.endswith("the fit needs 3")


def test_title_gives_the_basin_entropy(tmp_path):
    title = plot_basins.plot(read_basins(basins_file(tmp_path / "b.h5", entropy=True))).axes[0].get_title()
    assert "S_b 0.2, S_bb 0.6 (2 x 2 px boxes): S_bb <= ln 2 proves nothing\nuncertainty exponent not fitted" in title
    old = plot_basins.plot(read_basins(basins_file(tmp_path / "old.h5"))).axes[0].get_title()
    assert "S_b" not in old


def test_legend_names_regime_kcon_softness_and_fraction(tmp_path):
    fig = plot_basins.plot(read_basins(basins_file(tmp_path / "b.h5")))
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert "(1,1) k_con 8.96 soft: 52.3 %" in texts
    assert "(3,3) k_con 2.5: 47.7 %" in texts
    assert "unresolved or unlisted: 1 pixels" in texts
    assert "rest state" in texts
    title = fig.axes[0].get_title()
    assert "m2 = 310 kg" in title and "E2 = 1e+06 Pa" in title and "fixed x2=0.05 v2=0" in title


def test_png_written(tmp_path):
    out = tmp_path / "b.png"
    proc = run([*SCRIPT, str(basins_file(tmp_path / "b.h5")), "-o", str(out), "--dpi", "50"])
    assert proc.returncode == 0, proc.stderr
    assert png_size(out) == (450, 325)


def test_bad_file_is_one_line(tmp_path):
    bad = tmp_path / "bad.h5"
    with h5py.File(bad, "w") as f:
        f["x"] = np.zeros(3)
    proc = run([*SCRIPT, str(bad), "-o", str(tmp_path / "b.png")])
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and f"{bad}: not a vibromap basins file (no root attribute 'version')" in proc.stderr
    missing = run([*SCRIPT, str(tmp_path / "none.h5")])
    assert missing.returncode == 2 and "no such file" in missing.stderr
    assert not (tmp_path / "b.png").exists()
