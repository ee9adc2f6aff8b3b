"""Scene.with_ of model parameters set to numbers (set on the point, no reading of the scene)
against the reader: the same point, text, answers and messages.

Run by ctest as test_api.py is (tests/python/python_tests.cmake).
"""

import pickle

import numpy as np
import pytest

import vibromap

TABLE2 = "jobs/paper/table2.toml"


def read_again(scene, **keys):
    """The scene the reader gives for the same overrides (a string value always goes through it)."""
    return scene.with_(**{k: repr(float(v)) if isinstance(v, float) else str(v) for k, v in keys.items()})


@pytest.mark.parametrize("keys", [
    {"contact.E2": 2.5e6},
    {"contact.E2": 1234567.891011, "forcing.omega": 6.9},
    {"system.omega2": 3.0},          # a pair's other form: replaces k2
    {"system.k2": 4000},             # an int
    {"system.D": 0.07},
    {"forcing.F0": 1e-300},
])
def test_numbers_give_the_readers_scene(keys):
    base = vibromap.Scene.from_toml(TABLE2)
    fast, slow = base.with_(**keys), read_again(base, **keys)
    assert fast.to_toml() == slow.to_toml()
    for name in vibromap.Scene():
        assert repr(fast[name]) == repr(slow[name]), name
    a, b = vibromap.run(fast).to_dict(), vibromap.run(slow).to_dict()
    a.pop("wall_s", None), b.pop("wall_s", None)
    assert a == b


def test_a_chain_of_copies_has_the_chains_text():
    base = vibromap.Scene.from_toml(TABLE2)
    fast = base
    slow = base
    for e in np.geomspace(5e5, 5e6, 20):
        fast = fast.with_(**{"contact.E2": float(e)})
        slow = slow.with_(**{"contact.E2": repr(float(e))})
    assert fast.to_toml() == slow.to_toml() and fast["contact.E2"] == slow["contact.E2"]
    assert pickle.loads(pickle.dumps(fast)) == slow


@pytest.mark.parametrize("keys", [
    {"contact.E2": -1.0},
    {"contact.E2": float("nan")},
    {"forcing.omega": 1e-9},         # a rule that combines keys (the forcing against the natural frequencies)
    {"system.m2": 0},
])
def test_refused_numbers_give_the_readers_message(keys):
    base = vibromap.Scene.from_toml(TABLE2)
    with pytest.raises(vibromap.SceneError) as fast:
        base.with_(**keys)
    with pytest.raises(vibromap.SceneError) as slow:
        read_again(base, **keys)
    assert str(fast.value) == str(slow.value)
