"""`vibromap continue` steps any parameter (a real key of [system], [contact] or [forcing]) as
--param and --param2, named by the key table.

The force is F(t) = lambda F0 cos(omega t + phi0), so the dynamics depend on lambda and F0 only
through their product: the fold curve of Table 2's (1,1) in (omega, lambda) over [0.9, 1.1] is the
fold curve in (omega, F0) over [450, 550] N with F0 = 500 lambda. Each lambda curve point is
checked against the F0 curve, interpolated in omega along its arm of the same side of the cusp.
"""
import json
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import vibromap_stdout as vibromap  # noqa: E402

SCENE = "jobs/paper/table2.toml"
BRANCH = ["continue", SCENE, "--param", "forcing.omega", "--from", "7.23", "--to", "8.3", "--pd-depth", "0",
          "--curve", "fold", "--format", "json"]
REL = 1e-7  # both curves are corrected to Newton's tolerance (1e-9 of the scaled state)


def folds(param2, lo, hi):
    out = json.loads(vibromap(*BRANCH, "--param2", param2, "--from2", lo, "--to2", hi))
    return [c for c in out["curves"] if c["n"] == 1]


@pytest.fixture(scope="module")
def curves():
    return folds("forcing.lambda", "0.9", "1.1"), folds("forcing.F0", "450", "550")


def test_lambda_is_continued_as_a_parameter(curves):
    by_lambda, by_f0 = curves
    assert len(by_lambda) == len(by_f0) == 2  # Table 2's (1,1) has two folds in [7.23, 8.3]
    for c in by_lambda:
        lam = [p["param2"] for p in c["points"]]
        assert min(lam) == pytest.approx(0.9) and max(lam) == pytest.approx(1.1)


def test_the_lambda_fold_curve_is_the_F0_fold_curve(curves):
    by_lambda, by_f0 = curves
    for c, d in zip(sorted(by_lambda, key=lambda c: c["points"][0]["param"]),
                    sorted(by_f0, key=lambda c: c["points"][0]["param"])):
        f0 = np.array([p["param2"] for p in d["points"]])
        omega = np.array([p["param"] for p in d["points"]])
        order = np.argsort(f0)
        for p in c["points"]:
            expected = np.interp(500.0 * p["param2"], f0[order], omega[order])
            assert p["param"] == pytest.approx(expected, rel=REL, abs=0), p
