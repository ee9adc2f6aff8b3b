"""The Python package against the command line: the same numbers, messages and keys.

Run by ctest (tests/python/python_tests.cmake) with PYTHONPATH at the build tree's package
and VIBROMAP_EXE the built program; in the source directory, so scenes are named as a user
names them.
"""

import concurrent.futures
import json
import os
import pickle
import signal
import subprocess
import sys
import time

import pytest

import vibromap

EXE = os.environ.get("VIBROMAP_EXE", "build/vibromap")
TABLE1 = "jobs/paper/table1.toml"
TABLE2 = "jobs/paper/table2.toml"
# Timings differ from run to run; every other quantity must be equal.
TIMINGS = ("wall_s", "initial_states_per_s")


def cli(*args):
    return subprocess.run([EXE, *args], capture_output=True, text=True)


def cli_json(scene, *sets, flags=()):
    args = ["run", scene, "--format", "json", *flags]
    for s in sets:
        args += ["--set", s]
    p = cli(*args)
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def cli_error(scene, *sets):
    args = ["run", scene, "--format", "json"]
    for s in sets:
        args += ["--set", s]
    p = cli(*args)
    assert p.returncode == 2 and p.stdout == ""
    prefix = "vibromap: error: "
    assert p.stderr.startswith(prefix) and p.stderr.count("\n") == 1
    return p.stderr[len(prefix):].rstrip("\n")


def without_timings(d):
    return {k: v for k, v in d.items() if k not in TIMINGS}


def assert_bitwise_equal(a, b, where="result"):
    """Equal values, floats equal in their shortest repr (so -0.0 differs from 0.0, NaN is null)."""
    assert type(a) is type(b), f"{where}: {a!r} vs {b!r}"
    if isinstance(a, dict):
        assert list(a) == list(b), where
        for k in a:
            assert_bitwise_equal(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_bitwise_equal(x, y, f"{where}[{i}]")
    else:
        assert repr(a) == repr(b), f"{where}: {a!r} vs {b!r}"


@pytest.mark.parametrize(
    "scene, sets",
    [
        (TABLE1, ()),
        (TABLE2, ()),
        (TABLE2, ("contact.E2=2.5e6", "forcing.omega=6.9", "solver.method=dopri5")),
    ],
)
def test_run_equals_the_command_line_bit_for_bit(scene, sets):
    expected = without_timings(cli_json(scene, *sets))
    keys = dict(s.split("=", 1) for s in sets)
    typed = {k: (v if k == "solver.method" else float(v)) for k, v in keys.items()}
    r = vibromap.run(vibromap.Scene.from_toml(scene).with_(**typed))
    assert_bitwise_equal(without_timings(r.to_dict()), expected)
    assert r.k_con == expected["k_con"] and r.regime == expected["regime"] and r.soft == expected["soft"]
    # The same through from_toml's keys and run's keys.
    assert without_timings(vibromap.run(vibromap.Scene.from_toml(scene, **typed)).to_dict()) == expected
    assert without_timings(vibromap.run(vibromap.Scene.from_toml(scene), **typed).to_dict()) == expected


@pytest.mark.parametrize("labels", [False, True])
def test_census_equals_the_command_line_bit_for_bit(labels):
    flags = ("--census", "--labels") if labels else ("--census",)
    expected = without_timings(cli_json(TABLE2, "census.initial_conditions=12", flags=flags))
    c = vibromap.census(vibromap.Scene.from_toml(TABLE2), k=12, labels=labels)
    assert_bitwise_equal(without_timings(c.to_dict()), expected)
    assert [a["regime"] for a in c.attractors] == [a["regime"] for a in expected["attractors"]]
    assert sum(c.fractions().values()) == pytest.approx(1.0)
    assert pickle.loads(pickle.dumps(c)) == c


def test_trajectory_equals_the_command_lines_file_bit_for_bit(tmp_path):
    import h5py
    import numpy as np

    path = tmp_path / "traj.h5"
    sets = ("analysis.trajectory_periods=3", "analysis.trajectory_samples=100")
    args = ["run", TABLE2, "--trajectory", str(path)] + [a for s in sets for a in ("--set", s)]
    assert cli(*args).returncode == 0
    ds = vibromap.trajectory(vibromap.Scene.from_toml(TABLE2), periods=3, samples=100)
    with h5py.File(path) as f:
        assert list(ds.coords) == ["t"] and sorted(ds.data_vars) == sorted(k for k in f if k != "t")
        assert ds.sizes["t"] == f["t"].shape[0] >= 300  # 100 a period, and more in contact
        for name in f:
            assert np.array_equal(ds[name].values, f[name][...]), name
            units = f[name].attrs["units"]
            assert ds[name].attrs["units"] == (units.decode() if isinstance(units, bytes) else units), name
        for name in ("T", "n", "k", "T_con", "k_con"):
            assert ds.attrs[name] == f.attrs[name], name
    assert ds.attrs["result"].k_con == ds.attrs["k_con"]


def test_scene_defaults_are_the_programs():
    # jobs/reference.toml gives every key its default (a test of tests/cli holds it to `vibromap keys --toml`).
    expected = without_timings(cli_json("jobs/reference.toml", "contact.E2=1e6"))
    r = vibromap.run(vibromap.Scene(**{"contact.E2": 1e6}))
    assert_bitwise_equal(without_timings(r.to_dict()), expected)


def test_a_bad_key_raises_scene_error_with_the_command_lines_message():
    message = cli_error(TABLE2, "contact.E3=1")
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.Scene.from_toml(TABLE2).with_(**{"contact.E3": 1})
    assert str(e.value) == message
    assert isinstance(e.value, ValueError)
    assert type(e.value).__module__ == "vibromap"  # as tracebacks name it
    assert message.startswith("jobs/paper/table2.toml: --set contact.E3=1: unknown key 'E3' in [contact]")


def test_a_bad_value_raises_scene_error_with_the_command_lines_message():
    message = cli_error(TABLE2, "contact.E2=-1")
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.run(vibromap.Scene.from_toml(TABLE2), **{"contact.E2": -1})
    assert str(e.value) == message == "jobs/paper/table2.toml: --set contact.E2=-1: [contact] E2 = -1: must be > 0 (Pa)"
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.Scene(m2="abc")
    assert str(e.value) == 'Scene(): --set m2=abc: [system] m2 = "abc": must be a finite number > 0 (kg)'
    missing = cli_error("no/such/scene.toml")
    with pytest.raises(vibromap.SceneError) as e:
        vibromap.Scene.from_toml("no/such/scene.toml")
    assert str(e.value) == missing


def test_results_and_scenes_pickle():
    scene = vibromap.Scene.from_toml(TABLE2).with_(**{"forcing.omega": 7.1})
    r = vibromap.run(scene)
    r2 = pickle.loads(pickle.dumps(r))
    assert r2 == r and r2.to_dict() == r.to_dict() and r2.k_con == r.k_con and repr(r2) == repr(r)
    scene2 = pickle.loads(pickle.dumps(scene))
    assert scene2 == scene and scene2.path == TABLE2 and scene2["forcing.omega"] == 7.1
    assert without_timings(vibromap.run(scene2).to_dict()) == without_timings(r.to_dict())


def test_with_returns_a_changed_copy():
    scene = vibromap.Scene.from_toml(TABLE2)
    text = scene.to_toml()
    changed = scene.with_(E2=2e6, omega2=3.0)
    assert scene["contact.E2"] == 1e6 and changed["contact.E2"] == 2e6
    assert scene.to_toml() == text and changed.to_toml() != text
    # A key of a pair replaces its partner: k2 follows omega2.
    assert changed["system.k2"] == changed["system.m2"] * 3.0**2
    assert scene["system.omega2"] == 3.606


def key_rows_of_the_command_line():
    """The point keys of `vibromap keys` (its first table), cut at the header's columns."""
    lines = cli("keys").stdout.splitlines()
    header = lines[0]
    starts = [header.index(c) for c in ("key", "default", "unit", "allowed", "meaning")]
    rows = {}
    for line in lines[1:]:
        if not line.strip():
            break
        cells = [line[a:b].strip() for a, b in zip(starts, starts[1:] + [None])]
        rows[cells[0]] = cells[1:]
    return rows


def test_key_info_is_the_key_table():
    rows = key_rows_of_the_command_line()
    infos = vibromap.Scene.keys()
    assert [k.name for k in infos] == list(rows)
    for k in infos:
        meaning = k.meaning + (f"; or give {k.partner}" if k.partner else "")
        assert [k.default_text, k.unit, k.allowed, meaning] == rows[k.name], k.name
    e2 = vibromap.Scene.key("E2")
    assert (e2.name, e2.unit, e2.default, e2.bounds) == ("contact.E2", "Pa", 2.099e11, (0.0, float("inf"), True, False))
    assert vibromap.Scene.key("system.k1").default == 1000.0 * 6.283**2
    assert vibromap.Scene.key("solver.method").choices == ("hybrid", "dopri5", "rk4")
    assert vibromap.Scene()["solver.method"] == "hybrid"


def test_threads_give_the_serial_answers():
    base = vibromap.Scene.from_toml(TABLE2)
    scenes = [base.with_(**{"contact.E2": e}) for e in (0.8e6, 1.0e6, 1.3e6, 1.7e6)]
    serial = [without_timings(vibromap.run(s).to_dict()) for s in scenes]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        threaded = [without_timings(r.to_dict()) for r in pool.map(vibromap.run, scenes)]
    assert threaded == serial


# A point that takes minutes: rk4 with 10^7 steps per period (the command line had not finished
# it after 20 s on the 2-core machine of docs/benchmarks.md).
LONG = ("solver.method", "rk4"), ("solver.rk4_steps", 10_000_000), ("solver.max_steps", 10_000_000_000)

INTERRUPTED = f"""
import sys, vibromap
scene = vibromap.Scene.from_toml({TABLE2!r}, **dict({LONG!r}))
try:
    print("started", flush=True)
    vibromap.run(scene)
    print("finished")
except KeyboardInterrupt:
    print("KeyboardInterrupt")
"""


def test_ctrl_c_stops_a_long_run_with_keyboard_interrupt():
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    child = subprocess.Popen([sys.executable, "-c", INTERRUPTED], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert child.stdout.readline() == "started\n"
        time.sleep(0.5)  # into the solve (a signal before it is Python's own KeyboardInterrupt)
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)  # a bound for a broken stop only
    finally:
        child.kill()
    assert out == "KeyboardInterrupt\n" and child.returncode == 0
