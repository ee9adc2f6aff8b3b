"""Files of every kind vibromap writes, made by the built program (VIBROMAP_EXE, set by ctest),
small enough to be made in seconds: for the tests of vibromap.files and vibromap.plot, and for
tests/campaigns/outputs/test_xarray_outputs.py (every file in xarray's two engines)."""

from __future__ import annotations

import os
import subprocess

import pytest

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
TABLE1, TABLE2 = (os.path.join(REPO, "jobs", "paper", f"table{i}.toml") for i in (1, 2))

SWEEP = """
[system]
m2 = 310.0
omega2 = 3.606

[sweep]
E1 = { from = 1e9, to = 2.1e11, n = 2, scale = "log" }
E2 = { from = 1e6, to = 2e6, n = 3 }
store = ["k_con", "T_con", "F_max"]
"""
REFINED = SWEEP.replace('store = ["k_con", "T_con", "F_max"]', 'store = ["k_con"]\nrefine = 1\nrefine_on = ["regime"]')
CENSUS = """
[system]
m2 = 310.0
omega2 = 3.606

[census]
initial_conditions = 4
seed = 3
max_attractors = 3

[sweep]
E1 = { from = 1e9, to = 2.1e11, n = 2, scale = "log" }
E2 = { from = 2e4, to = 1e7, n = 2, scale = "log" }
store = ["k_con"]
"""
# The bistable Table 2 point, seeded from a 2-cell map, with a soft-fraction re-check of the best
# point (its census groups in the file; tests/campaigns/multistart/test_optimise_mpi.py's ROBUST,
# smaller).
OPTIMISE = """
[system]
m2 = 310.0
omega2 = 3.606

[contact]
E1 = 1.4e10
E2 = 1e6

[census]
initial_conditions = 4

[sweep]
E2 = { from = 8e5, to = 1.2e6, n = 2, scale = "log" }
store = ["k_con", "T_con", "F_max"]

[optimise]
E2 = { min = 8e5, max = 1.2e6, scale = "log" }
seeds = 1
algorithm = "bobyqa"
max_evaluations = 4
best = 1
min_soft_fraction = 0.1
soft_check_initial_conditions = 8
"""
BASINS_GRID = "4x3"  # x1 by v1 pixels


def exe() -> str:
    path = os.environ.get("VIBROMAP_EXE")
    if not path:
        pytest.skip("no vibromap program (VIBROMAP_EXE is set by ctest)")
    return path


def make_all(tmp, program: str | None = None, env: dict | None = None, text_files: bool = True) -> dict:
    """{name: path} of one file of each kind, made in the folder tmp by `program` (default:
    VIBROMAP_EXE) in `env`: the HDF5 files, and with text_files the restitution JSON and the
    accuracy CSV. Made once a session for the postprocess tests (conftest's fixture `made`) and
    once for tests/campaigns/outputs/test_xarray_outputs.py."""
    program = program or exe()

    def vibromap(*args) -> subprocess.CompletedProcess:
        proc = subprocess.run([program, *map(str, args)], env=env, capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, proc.stderr
        return proc

    def scene(name, text):
        (tmp / name).write_text(text)
        return tmp / name

    out = {name: tmp / f"{name}.h5" for name in ("map", "refined", "census", "trajectory", "basins", "optimise",
                                                  "branch", "orbit", "curves")}
    vibromap("sweep", scene("map.toml", SWEEP), "-q", "-o", out["map"])
    vibromap("sweep", scene("refined.toml", REFINED), "-q", "-o", out["refined"])
    vibromap("sweep", scene("census.toml", CENSUS), "-q", "-o", out["census"])
    vibromap("run", TABLE1, "-t", out["trajectory"])
    vibromap("basins", TABLE2, "--grid", BASINS_GRID, "-q", "-o", out["basins"])
    vibromap("optimise", scene("optimise.toml", OPTIMISE), "-q", "-o", out["optimise"])
    vibromap("continue", TABLE1, "-p", "forcing.omega", "--from", "7.2", "--to", "7.25", "-o", out["branch"])
    vibromap("orbit-diagram", TABLE1, "-p", "omega", "--from", "7.2", "--to", "7.25", "-n", "3", "--transient", "5",
             "--keep", "2", "-q", "-o", out["orbit"])
    vibromap("continue", TABLE2, "-p", "omega", "--from", "11", "--to", "7.3", "--pd-depth", "0", "--curve", "grazing",
             "--param2", "F0", "--from2", "300", "--to2", "700", "-o", out["curves"])
    out["optimise_map"], out["optimise_trajectory"] = tmp / "optimise_map.h5", tmp / "optimise_trajectory.h5"
    if text_files:
        out["restitution"] = tmp / "restitution.json"
        out["restitution"].write_text(vibromap("restitution", "--format", "json").stdout)
        out["accuracy"] = tmp / "accuracy.csv"
        vibromap("accuracy", TABLE2, "-q", "--csv", out["accuracy"])
    return out
