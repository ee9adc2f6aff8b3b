"""Files of every kind vibromap writes, made by the built program (VIBROMAP_EXE, set by ctest),
small enough to be made in seconds: for the tests of vibromap.files and vibromap.plot.
Scenes as in tests/campaigns/outputs/test_xarray_outputs.py."""

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
OPTIMISE = """
[system]
m2 = 310.0
omega2 = 3.606

[sweep]
E2 = { from = 8e5, to = 1.2e6, n = 2, scale = "log" }
store = ["k_con", "T_con", "F_max"]

[optimise]
E2 = { min = 8e5, max = 1.2e6, scale = "log" }
seeds = 1
algorithm = "bobyqa"
max_evaluations = 4
best = 1
"""


def exe() -> str:
    path = os.environ.get("VIBROMAP_EXE")
    if not path:
        pytest.skip("no vibromap program (VIBROMAP_EXE is set by ctest)")
    return path


def vibromap(*args) -> None:
    proc = subprocess.run([exe(), *map(str, args)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr


def make_all(tmp) -> dict:
    """{name: path} of one file of each kind, made in the folder tmp (conftest's session
    fixture `made`: once for all the tests that read them)."""
    def scene(name, text):
        (tmp / name).write_text(text)
        return tmp / name

    out = {name: tmp / f"{name}.h5" for name in ("map", "refined", "census", "trajectory", "basins", "optimise",
                                                  "branch", "orbit", "curves")}
    vibromap("sweep", scene("map.toml", SWEEP), "-q", "-o", out["map"])
    vibromap("sweep", scene("refined.toml", REFINED), "-q", "-o", out["refined"])
    vibromap("sweep", scene("census.toml", CENSUS), "-q", "-o", out["census"])
    vibromap("run", TABLE1, "-t", out["trajectory"])
    vibromap("basins", TABLE2, "--grid", "4x3", "-q", "-o", out["basins"])
    vibromap("optimise", scene("optimise.toml", OPTIMISE), "-q", "-o", out["optimise"])
    vibromap("continue", TABLE1, "-p", "forcing.omega", "--from", "7.2", "--to", "7.25", "-o", out["branch"])
    vibromap("orbit-diagram", TABLE1, "-p", "omega", "--from", "7.2", "--to", "7.25", "-n", "3", "--transient", "5",
             "--keep", "2", "-q", "-o", out["orbit"])
    vibromap("continue", TABLE2, "-p", "omega", "--from", "11", "--to", "7.3", "--pd-depth", "0", "--curve", "grazing",
             "--param2", "F0", "--from2", "300", "--to2", "700", "-o", out["curves"])
    out["restitution"] = tmp / "restitution.json"
    proc = subprocess.run([exe(), "restitution", "--format", "json"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out["restitution"].write_text(proc.stdout)
    out["accuracy"] = tmp / "accuracy.csv"
    vibromap("accuracy", TABLE2, "-q", "--csv", out["accuracy"])
    return out
