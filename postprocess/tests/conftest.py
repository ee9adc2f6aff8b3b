"""Shared fixtures for the postprocess tests: the package's directory on sys.path, the scripts' command, an analytic
trajectory file written with h5py in the layout of src/io/trajectory_file.cpp (stamped with its
version and attribute checksum, stamp.py), and the map files of map_cases.py (map1d, map2d,
map3d)."""

from __future__ import annotations

import math
import os
import struct
import subprocess
import sys

import h5py
import matplotlib.colors
import numpy as np
import pytest

POSTPROCESS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if POSTPROCESS_DIR not in sys.path:
    sys.path.insert(0, POSTPROCESS_DIR)
# The scripts run as `python -m vibromap SCRIPT` in subprocesses, which find the package here.
os.environ["PYTHONPATH"] = os.pathsep.join(p for p in (POSTPROCESS_DIR, os.environ.get("PYTHONPATH")) if p)
LAUNCHER = os.path.join(POSTPROCESS_DIR, "vibromap-post")


def script(name: str) -> list[str]:
    """The command that runs the postprocess script `name` with this interpreter, as vibromap-post does."""
    return [sys.executable, "-m", "vibromap", name]

# The analytic motion of tests/io/test_trajectory_file.cpp (harmonic_summary): keep them equal, so
# that a file written by the C++ writer can be checked against the same formulas.
OMEGA = 7.23  # forcing frequency, rad/s
T = 2.0 * math.pi / OMEGA  # forcing period, s
D, A1, A2 = 0.05, 0.02, 0.01  # clearance and amplitudes, m
F0, FC_MAX = 500.0, 1.0e5  # external force amplitude and contact force peak, N
T_CON = 7.81e-4  # s
UNITS = {"t": "s", "x1": "m", "x2": "m", "v1": "m/s", "v2": "m/s", "Fc": "N", "F": "N"}


def analytic_trajectory(samples_per_period: int, periods: int) -> dict[str, np.ndarray]:
    """x1 = A1 sin(omega t), x2 = D + A2 cos(omega t), exact velocities, Fc a half-sine pulse
    of height FC_MAX, F = F0 cos(omega t), sampled at t = T i / samples_per_period."""
    i = np.arange(samples_per_period * periods + 1)
    t = T * i / samples_per_period
    phase = OMEGA * t
    pulse = np.sin(phase)
    return {
        "t": t,
        "x1": A1 * np.sin(phase),
        "x2": D + A2 * np.cos(phase),
        "v1": A1 * OMEGA * np.cos(phase),
        "v2": -A2 * OMEGA * np.sin(phase),
        "Fc": np.where(pulse > 0.0, FC_MAX * pulse, 0.0),
        "F": F0 * np.cos(phase),
    }


def write_trajectory_h5(path, columns: dict[str, np.ndarray], regime: str = "(1,1)", n: int = 1, k: int = 1) -> None:
    from stamp import stamp

    with h5py.File(path, "w") as f:
        for name, values in columns.items():
            f.create_dataset(name, data=values, dtype="f8")
            f[name].attrs["units"] = UNITS[name]
        f.attrs["T"] = T
        f.attrs["regime"] = regime
        f.attrs["n"] = np.int64(n)
        f.attrs["k"] = np.int64(k)
        f.attrs["T_con"] = T_CON
        f.attrs["k_con"] = T / T_CON
        f.attrs["scene"] = "[system]\nm1 = 1000.0\n"
        f.attrs["vibromap_version"] = "0.1.0"
    stamp(path, "trajectory file")


@pytest.fixture
def trajectory_file(tmp_path):
    """(path, columns) of an analytic trajectory over 3 forcing periods, 200 samples each."""
    columns = analytic_trajectory(200, 3)
    path = tmp_path / "traj.h5"
    write_trajectory_h5(path, columns)
    return path, columns


@pytest.fixture
def map2d(tmp_path):
    """(path, arrays) of map_cases.py's 2-D map, with k_con and T_con."""
    import map_cases

    return map_cases.write_map2d(tmp_path)


@pytest.fixture
def map3d(tmp_path):
    """(path, k_con) of map_cases.py's 3-D map; cell [3, 2, 4] not done."""
    import map_cases

    return map_cases.write_map3d(tmp_path)


@pytest.fixture
def map1d(tmp_path):
    """The path of map_cases.py's 1-D map over E2."""
    import map_cases

    return map_cases.write_map1d(tmp_path)


def run(args, **env):
    """Runs a script as a subprocess with a private matplotlib config dir; text output."""
    environment = dict(os.environ, MPLCONFIGDIR=os.environ.get("MPLCONFIGDIR", "/tmp/vibromap-mplconfig"), **env)
    return subprocess.run(args, capture_output=True, text=True, env=environment, timeout=120)


def png_size(path) -> tuple[int, int]:
    """(width, height) from the PNG's IHDR chunk."""
    with open(path, "rb") as f:
        header = f.read(24)
    assert header[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG file"
    return struct.unpack(">II", header[16:24])


def pixels_near(image: np.ndarray, color: str, tol: float = 0.03) -> int:
    """Number of pixels within `tol` (per RGB channel) of a matplotlib colour."""
    rgb = np.array(matplotlib.colors.to_rgb(color))
    return int(np.all(np.abs(image[..., :3] - rgb) < tol, axis=-1).sum())


def inside(segments, point) -> bool:
    """Whether point (x, y) lies inside the region that axis-parallel segments ((2, 2) arrays)
    outline: a ray from it towards +x crosses an odd number of the vertical ones."""
    x, y = point
    crossings = 0
    for (x0, y0), (x1, y1) in segments:
        if x0 == x1 and x0 > x and min(y0, y1) <= y < max(y0, y1):
            crossings += 1
    return crossings % 2 == 1


@pytest.fixture(scope="session")
def made(tmp_path_factory):
    """{name: path}: one file of each kind vibromap writes, made once by the built program
    (real_files.py; the tests that use it skip where VIBROMAP_EXE is not set)."""
    import real_files

    return real_files.make_all(tmp_path_factory.mktemp("real-files"))
