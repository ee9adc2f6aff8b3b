"""vibromap.branch, curve, optimise and sweep against the command line: the same JSON, the same
files bit for bit, the command's messages, a stopped map resumed to the uninterrupted one.

Run by ctest with PYTHONPATH at the build tree's package and VIBROMAP_EXE the built program
(tests/python/python_tests.cmake), in the source directory.
"""

import json
import os
import signal
import subprocess
import sys

import h5py
import numpy as np
import pytest

import vibromap

EXE = os.environ.get("VIBROMAP_EXE", "build/vibromap")
TABLE2 = "jobs/paper/table2.toml"
MPIRUN = ["mpirun", "-n", "2", "--allow-run-as-root"] if os.geteuid() == 0 else ["mpirun", "-n", "2"]
# Quantities of a run, not of its answer: they differ from run to run.
RUN_ATTRIBUTES = ("scene", "summary", "attribute_checksum", "ranks", "vibromap_version")
RUN_DATASETS = ("wall_s",)  # each cell's solve time

LINE = """# E2 and omega through Table 2: a small map.
[system]
m1 = 1000.0
m2 = 310.0
omega1 = 6.283
omega2 = 3.606
D = 0.05
[contact]
E1 = 1.4e10
E2 = 1.0e6
R1 = 2.0
R2 = 2.0
q = 0.319
[forcing]
F0 = 500.0
omega = 7.23
[sweep]
"contact.E2" = {{ from = 5e5, to = 5e6, n = {n} }}
"forcing.omega" = {{ from = 7.0, to = 7.4, n = {m} }}
store = ["T_con", "k_con", "F_max", "z_ratio"]
checkpoint_interval = 0.2
progress_interval = 0.1
"""


def cli(*args, mpi=()):
    return subprocess.run([*mpi, EXE, *args], capture_output=True, text=True)


def cli_error(*args):
    p = cli(*args)
    assert p.returncode == 2, p.stderr
    lines = [line for line in p.stderr.splitlines() if line.startswith("vibromap: error: ")]
    assert len(lines) == 1, p.stderr
    return lines[0][len("vibromap: error: "):]


def h5_arrays(path):
    """Every dataset of an HDF5 file (groups included) by its name, and the root's attributes."""
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[...])
                     if isinstance(obj, h5py.Dataset) and name not in RUN_DATASETS else None)
        attrs = {k: v for k, v in f.attrs.items() if k not in RUN_ATTRIBUTES}
    return out, attrs


def assert_same_arrays(a, b):
    assert a.keys() == b.keys()
    for name in a:
        x, y = a[name], b[name]
        assert x.dtype == y.dtype and x.shape == y.shape, name
        if x.dtype.kind == "f":
            assert np.array_equal(x.view(np.uint64 if x.itemsize == 8 else np.uint32),
                                  y.view(np.uint64 if y.itemsize == 8 else np.uint32)), name
        else:
            assert np.array_equal(x, y), name


def assert_dataset_is_file(ds, path, group=None):
    """The Dataset holds the file's values bit for bit."""
    with h5py.File(path, "r") as f:
        g = f[group] if group else f
        for name, var in ds.variables.items():
            if name in RUN_DATASETS:
                continue
            if name not in g and name.endswith("_name") and name[:-len("_name")] in g:
                continue  # a code's names, which vibromap.files.open puts beside it
            stored = g[name][...]
            assert var.values.dtype == stored.dtype and var.values.shape == stored.shape, name
            assert var.values.tobytes() == stored.tobytes(), name


def test_branch_is_continue_bit_for_bit(tmp_path):
    study = ["--param", "forcing.omega", "--from", "7.0", "--to", "7.6", "--pd-depth", "0"]
    p = cli("continue", TABLE2, *study, "--format", "json", "-o", str(tmp_path / "cli.h5"))
    assert p.returncode == 0, p.stderr
    b = vibromap.branch(vibromap.Scene.from_toml(TABLE2), "forcing.omega", 7.0, 7.6, pd_depth=0,
                        output=tmp_path / "py.h5")
    assert b.to_dict() == json.loads(p.stdout)
    assert json.dumps(b.to_dict()) == json.dumps(json.loads(p.stdout))  # every float's repr
    assert_same_arrays(h5_arrays(tmp_path / "cli.h5")[0], h5_arrays(tmp_path / "py.h5")[0])
    assert h5_arrays(tmp_path / "cli.h5")[1] == h5_arrays(tmp_path / "py.h5")[1]
    assert_dataset_is_file(b.dataset, tmp_path / "cli.h5")
    assert b.key == "forcing.omega" and b.params[0] == 7.0 and len(b.points) == b.dataset.sizes["point"]


def test_curve_is_continue_bit_for_bit(tmp_path):
    study = ["--param", "forcing.omega", "--from", "7.23", "--to", "8.3", "--pd-depth", "0", "--curve", "fold",
             "--param2", "forcing.F0", "--from2", "480", "--to2", "520"]
    p = cli("continue", TABLE2, *study, "--format", "json", "-o", str(tmp_path / "cli.h5"))
    assert p.returncode == 0, p.stderr
    scene = vibromap.Scene.from_toml(TABLE2)
    c = vibromap.curve(scene, "forcing.omega", 7.23, 8.3, "fold", "forcing.F0", 480, 520, pd_depth=0)
    assert json.dumps(c.to_dict()) == json.dumps(json.loads(p.stdout))
    assert [curve["kind"] for curve in c.curves] == ["fold"] * len(c.datasets) and c.datasets
    for i, ds in enumerate(c.datasets):
        assert_dataset_is_file(ds, tmp_path / "cli.h5", f"curve_{i}")
        assert ds.attrs["param2"] == "forcing.F0"


def test_sweep_on_two_ranks_is_the_command_lines_map(tmp_path):
    (tmp_path / "line.toml").write_text(LINE.format(n=6, m=2))
    p = cli("sweep", str(tmp_path / "line.toml"), "-q", "-o", str(tmp_path / "cli.h5"), mpi=MPIRUN)
    assert p.returncode == 0, p.stderr
    scene = vibromap.Scene.from_toml(tmp_path / "line.toml")
    ds = vibromap.sweep(scene, ranks=2, output=tmp_path / "py.h5", progress=False)
    cli_arrays, cli_attrs = h5_arrays(tmp_path / "cli.h5")
    py_arrays, py_attrs = h5_arrays(tmp_path / "py.h5")
    assert_same_arrays(cli_arrays, py_arrays)
    assert cli_attrs == py_attrs
    assert_dataset_is_file(ds, tmp_path / "cli.h5")
    assert json.loads(ds.attrs["summary"])["ranks"] == 2 and dict(ds.sizes) == {"E2": 6, "omega": 2}
    # The codes are named as vibromap.files.open names them: soft's by its flag_meanings.
    meanings = dict(zip(np.atleast_1d(ds.soft.attrs["flag_values"]).tolist(), ds.soft.attrs["flag_meanings"].split()))
    assert ds.soft_name.values.ravel().tolist() == [meanings[c] for c in ds.soft.values.ravel().tolist()]
    assert ds.attrs["vibromap_kind"] == "regime map"
    # The same map from a scene made in Python (given to the program as a temporary copy).
    text = vibromap.Scene.from_text((tmp_path / "line.toml").read_text(), "line.toml")
    ds2 = vibromap.sweep(text, output=tmp_path / "text.h5", progress=False)
    assert_same_arrays(cli_arrays, h5_arrays(tmp_path / "text.h5")[0])
    assert ds2.attrs["complete"] == 1


OPTIMISE = """
[optimise]
E2 = { min = 5e5, max = 5e6, scale = "log" }
seeds = 1
max_evaluations = 12
best = 1
"""


def without(d, names):
    if isinstance(d, dict):
        return {k: without(v, names) for k, v in d.items() if k not in names}
    return [without(x, names) for x in d] if isinstance(d, list) else d


def test_optimise_is_the_command_lines(tmp_path):
    (tmp_path / "opt.toml").write_text(open(TABLE2).read() + OPTIMISE)
    p = cli("optimise", str(tmp_path / "opt.toml"), "-q", "--format", "json", "-o", str(tmp_path / "cli.h5"))
    assert p.returncode == 0, p.stderr
    o = vibromap.optimise(vibromap.Scene.from_toml(tmp_path / "opt.toml"), output=tmp_path / "py.h5", progress=False)
    run_quantities = ("wall_s", "sweep_wall_s", "optimise_wall_s", "verify_wall_s", "output", "trajectory")
    expected = without(json.loads(p.stdout), run_quantities)
    assert json.dumps(without(o.to_dict(), run_quantities)) == json.dumps(expected)
    assert o.best[0]["params"]["E2"] == expected["best"][0]["params"]["E2"]
    assert_dataset_is_file(o.group("starts/000"), tmp_path / "cli.h5", "starts/000")
    assert o.trajectory is not None and o.trajectory.attrs["k_con"] == o.best[0]["k_con"]


def test_bad_input_raises_the_command_lines_message(tmp_path):
    scene = vibromap.Scene.from_toml(TABLE2)
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.branch(scene, "forcing.omega", 7.0, 7.0)
    assert str(e.value) == cli_error("continue", TABLE2, "--param", "forcing.omega", "--from", "7.0", "--to", "7.0")
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.branch(scene, "forcing.omegga", 7.0, 7.5)
    assert str(e.value) == cli_error("continue", TABLE2, "--param", "forcing.omegga", "--from", "7.0", "--to", "7.5")
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.sweep(scene, output=tmp_path / "none.h5", progress=False)  # Table 2 has no [sweep]
    assert str(e.value) == cli_error("sweep", TABLE2, "-o", str(tmp_path / "none.h5"))
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.sweep(scene, output=tmp_path / "none.h5", progress=False, **{"contact.E2": -1})
    assert str(e.value) == cli_error("sweep", TABLE2, "--set", "contact.E2=-1", "-o", str(tmp_path / "none.h5"))


# A sweep stopped by Ctrl-C in Python: the child prints "stopping" when it sees cells done and
# "KeyboardInterrupt" when the call raised it.
STOPPED = """
import sys, vibromap
scene = vibromap.Scene.from_toml(sys.argv[1])
try:
    vibromap.sweep(scene, output=sys.argv[2])
    print("finished", flush=True)
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
"""


def test_a_stopped_sweep_resumes_to_the_uninterrupted_map(tmp_path):
    (tmp_path / "line.toml").write_text(LINE.format(n=30, m=4))
    p = cli("sweep", str(tmp_path / "line.toml"), "-q", "-o", str(tmp_path / "whole.h5"))
    assert p.returncode == 0, p.stderr
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    child = subprocess.Popen([sys.executable, "-c", STOPPED, str(tmp_path / "line.toml"), str(tmp_path / "part.h5")],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        for line in child.stderr:  # the farm's progress lines, passed on by the call
            if line.startswith("sweep: ") and not line.startswith("sweep: 0/"):
                break
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)  # a bound for a broken stop only
    finally:
        child.kill()
    assert out == "KeyboardInterrupt\n" and child.returncode == 0
    assert not os.path.exists(tmp_path / "part.h5.lock")
    with h5py.File(tmp_path / "part.h5", "r") as f:  # a whole file: it opens, part of it done
        assert 0 < f.attrs["cells_done"] < 120 and f.attrs["complete"] == 0
    scene = vibromap.Scene.from_toml(tmp_path / "line.toml")
    ds = vibromap.sweep(scene, output=tmp_path / "part.h5", progress=False)  # resumes: the output exists
    summary = json.loads(ds.attrs["summary"])
    assert summary["cells_resumed"] > 0 and summary["cells_resumed"] + summary["cells_computed"] == 120
    assert_same_arrays(h5_arrays(tmp_path / "whole.h5")[0], h5_arrays(tmp_path / "part.h5")[0])


class FakeHandle:
    def __init__(self, shown):
        self.shown = [shown]

    def update(self, obj):
        self.shown.append(obj)


def test_a_notebook_shows_a_bar(tmp_path, monkeypatch):
    """In a Jupyter kernel (IPython stood in for: get_ipython() has a kernel) the progress is a
    bar updated in place, parsed from the farm's lines."""
    import types

    handles = []
    ipython = types.ModuleType("IPython")
    ipython.get_ipython = lambda: types.SimpleNamespace(kernel=object())
    display = types.ModuleType("IPython.display")
    display.HTML = type("HTML", (), {"__init__": lambda self, data: setattr(self, "data", data)})
    display.display = lambda obj, display_id: handles.append(FakeHandle(obj)) or handles[-1]
    ipython.display = display
    monkeypatch.setitem(sys.modules, "IPython", ipython)
    monkeypatch.setitem(sys.modules, "IPython.display", display)
    (tmp_path / "line.toml").write_text(LINE.format(n=6, m=2))
    ds = vibromap.sweep(vibromap.Scene.from_toml(tmp_path / "line.toml"), output=tmp_path / "nb.h5")
    assert len(handles) == 1 and ds.attrs["complete"] == 1
    last = handles[0].shown[-1]
    assert '<progress value="12" max="12"' in last.data and repr(last).startswith("sweep: 12/12 cells (100.0%)")
