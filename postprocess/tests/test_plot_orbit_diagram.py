"""Tests of postprocess/plot_orbit_diagram.py on an orbit-diagram file written with h5py in the
layout of include/vibromap/io/orbit_diagram_file.hpp: omega 5..7 (3 points), keep 2; the up
sweep holds x1 = omega / 100 twice, the down sweep -omega / 100 (so the two are told apart)."""
import os

import h5py
import numpy as np

import conftest
from conftest import png_size, run
from vibromap.plot import _orbit_diagram as plot_orbit_diagram
from stamp import stamp

SCRIPT = conftest.script("plot_orbit_diagram")


def diagram(path):
    omega = np.array([5.0, 6.0, 7.0])
    x1 = np.empty((2, 3, 2))
    x1[0] = (omega / 100)[:, None]
    x1[1] = (-omega / 100)[:, None]
    with h5py.File(path, "w") as f:
        f.create_dataset("omega", data=omega).attrs["units"] = "rad/s"
        f.create_dataset("direction", data=np.array([1, -1], dtype=np.int8))
        f.create_dataset("sample", data=np.arange(2, dtype=np.int32))
        for name in ("x1", "x2", "v1", "v2"):
            f.create_dataset(name, data=x1)
        f.attrs["key"] = "forcing.omega"
        f.attrs["vibromap_version"] = "0.1.0"
    stamp(path, "orbit-diagram file")


def test_both_sweeps_are_drawn_with_their_values(tmp_path):
    path = tmp_path / "od.h5"
    diagram(path)
    fig = plot_orbit_diagram.plot(str(path), "x1")
    up = [c for c in fig.axes[0].collections if c.get_gid() == "orbit-diagram-up"][0]
    down = [c for c in fig.axes[0].collections if c.get_gid() == "orbit-diagram-down"][0]
    np.testing.assert_allclose(up.get_offsets(), [[5, 0.05], [5, 0.05], [6, 0.06], [6, 0.06], [7, 0.07], [7, 0.07]])
    np.testing.assert_allclose(down.get_offsets()[:, 1], [-0.05, -0.05, -0.06, -0.06, -0.07, -0.07])
    assert fig.axes[0].get_xlabel() == "forcing.omega, rad/s"
    out = tmp_path / "od.png"
    proc = run([*SCRIPT, str(path), "-o", str(out)])
    assert proc.returncode == 0, proc.stderr
    assert png_size(out) == (1350, 825)


def test_a_file_of_another_kind_is_one_line_exit_2(tmp_path):
    path = tmp_path / "other.h5"
    with h5py.File(path, "w") as f:
        f.create_dataset("x", data=np.zeros(3))
    proc = run([*SCRIPT, str(path), "-o", str(tmp_path / "x.png")])
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1
    assert f"{path}: not a vibromap orbit-diagram file (no root attribute 'version')" in proc.stderr
