"""`vibromap continue` over keys spanning decades (issue #31): a key whose ends are both positive
and span a factor of 100 or more is continued in ln(KEY) and reported in its own units.

The demo plane (jobs/demo/e1_e2.toml): the level k_con = 10 found along contact.E2 in
[2e5, 2e7] Pa and continued in contact.E1 over the paper's box [2e4, 2.1e11] Pa. Continued in E1
itself (steps of ~1e10 Pa) the curve never went below E1 = 3.8e9 Pa; in ln(E1) it reaches the
soft region below 1e7 Pa, and a plain `vibromap run` at a point there has k_con = 10 to 1e-6.
The dynamics depend on the moduli only through the effective modulus
1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (docs/model.md), so the level curve is E* = const: checked
at every point, which also checks that the points are reported in Pa and not in ln Pa.
"""
import json
import math
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import vibromap_stdout as vibromap  # noqa: E402

SCENE = "jobs/demo/e1_e2.toml"
LEVEL = ["continue", SCENE, "--param", "contact.E2", "--from", "2e5", "--to", "2e7", "--curve", "level:k_con=10",
         "--param2", "contact.E1", "--from2", "2e4", "--to2", "2.1e11", "--format", "json"]


@pytest.fixture(scope="module")
def curves():
    return json.loads(vibromap(*LEVEL))["curves"]


def test_the_level_curve_reaches_the_soft_decades(curves):
    assert curves and all(c["kind"] == "level:k_con=10" for c in curves)
    E1 = [p["param2"] for c in curves for p in c["points"]]
    E2 = [p["param"] for c in curves for p in c["points"]]
    assert min(E1) < 1e7, min(E1)
    # reported in Pa (not ln Pa), inside the box
    assert all(2e4 <= e <= 2.1e11 for e in E1) and all(2e5 <= e <= 2e7 for e in E2)
    # dense enough to draw: every decade of E1 the curve spans holds points
    lo, hi = math.floor(math.log10(min(E1))), math.floor(math.log10(max(E1)))
    assert {math.floor(math.log10(e)) for e in E1} >= set(range(lo + 1, hi))
    # one curve of constant effective modulus (nu1 = nu2 = 0.3 in the scene)
    E_star = [1.0 / (0.91 / e1 + 0.91 / e2) for e1, e2 in zip(E1, E2)]
    assert max(E_star) - min(E_star) <= 1e-7 * min(E_star), (min(E_star), max(E_star))


def test_a_soft_point_has_k_con_ten_in_a_plain_run(curves):
    soft = [p for c in curves for p in c["points"] if p["param2"] < 1e7]
    p = soft[len(soft) // 2]
    run = json.loads(vibromap("run", SCENE, "--set", f"contact.E1={p['param2']!r}", "--set",
                              f"contact.E2={p['param']!r}", "--format", "json"))
    assert run["regime"] == "(1,1)"
    assert abs(run["k_con"] - 10.0) <= 1e-6 * 10.0, (p["param"], p["param2"], run["k_con"])
