"""`vibromap continue --curve` (issue #31): curves of codimension-one points in two parameters,
from the command line, checked against plain `vibromap run` and written as the curve file.

The level k_con = 10 of Table 2's (1,1) family, found along contact.E2 in [1e6, 2e6] Pa and
continued in contact.E1 over [1e9, 1e11] Pa: at three of its points (its ends and its middle)
`vibromap run` of the scene with both keys set finds the (1,1) orbit with k_con = 10 to 1e-6.
The JSON's points and the curve file's datasets are the same numbers.
"""
import json
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import vibromap_stdout as vibromap  # noqa: E402

h5py = pytest.importorskip("h5py")

LEVEL = ["continue", "jobs/paper/table2.toml", "--param", "contact.E2", "--from", "1e6", "--to", "2e6",
         "--curve", "level:k_con=10", "--param2", "contact.E1", "--from2", "1e9", "--to2", "1e11"]


@pytest.fixture(scope="module")
def level(tmp_path_factory):
    path = tmp_path_factory.mktemp("curves") / "level.h5"
    report = json.loads(vibromap(*LEVEL, "--format", "json", "-o", path))
    return report, path


def test_the_level_curve_has_k_con_ten_in_plain_runs(level):
    report, _ = level
    curves = report["curves"]
    assert [c["kind"] for c in curves] == ["level:k_con=10"]
    points = curves[0]["points"]
    assert len(points) > 5
    assert curves[0]["stop"] == "left the box at contact.E1 = 1e+11; left the box at contact.E1 = 1000000000"
    for p in (points[0], points[len(points) // 2], points[-1]):
        run = json.loads(vibromap("run", "jobs/paper/table2.toml", "--set", f"contact.E2={p['param']!r}",
                                  "--set", f"contact.E1={p['param2']!r}", "--format", "json"))
        assert run["regime"] == "(1,1)"
        assert abs(run["k_con"] - 10.0) < 1e-6, (p["param"], p["param2"], run["k_con"])
        assert abs(p["k_con"] - 10.0) < 1e-6


def test_the_curve_file_holds_the_json_points(level):
    report, path = level
    points = report["curves"][0]["points"]
    with h5py.File(path, "r") as f:
        assert f.attrs["vibromap_file"] == "curves"
        assert (f.attrs["param"], f.attrs["param2"]) == ("contact.E2", "contact.E1")
        assert (f.attrs["param_unit"], f.attrs["param2_unit"]) == ("Pa", "Pa")
        assert int(f.attrs["version"]) == 1
        g = f["curve_0"]
        assert g.attrs["kind"] == "level:k_con=10" and int(g.attrs["n"]) == 1
        assert g.attrs["stop"] == report["curves"][0]["stop"]
        np.testing.assert_array_equal(g["param"][()], [p["param"] for p in points])
        np.testing.assert_array_equal(g["param2"][()], [p["param2"] for p in points])
        np.testing.assert_array_equal(g["k_con"][()], [p["k_con"] for p in points])
        np.testing.assert_array_equal(g["multipliers_re"][()][:, 0], [p["multipliers"][0][0] for p in points])
        assert g["multipliers_re"].shape == (len(points), 4)
        assert g["codim2/param"].shape == (len(report["curves"][0]["codim2"]),)
        assert float(np.max(g["residual"][()])) <= 1e-9


def test_the_table_summarises_each_curve(level):
    out = vibromap(*LEVEL)
    assert "curves         1 in (contact.E2, contact.E1), started at contact.E1 = 14000000000" in out
    assert "  curve 0  level:k_con=10 (period 1 T): " in out
    assert "\n    stop: left the box at contact.E1 = 1e+11; left the box at contact.E1 = 1000000000\n" in out


def test_the_fold_curve_brackets_the_up_sweeps_jump_at_its_ends(tmp_path):
    """The fold of Table 2's (1,1) branch (omega 7.23 -> 8.3) as a curve over F0 in [400, 600] N
    ends on the box's sides; at both ends the orbit diagram swept up in omega in steps of
    0.01 rad/s is on the period-1 orbit at the last step below the curve's omega and off it
    (its two kept stroboscopic x1 differ) at the next: the jump comes within one step after the
    curve. (Measured 2026-11-26: 8.18 / 8.19 around 8.1812405 at 400 N, 8.24 / 8.25 around
    8.2420379 at 500 N, 8.28 / 8.29 around 8.2862560 at 600 N.)"""
    report = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--param", "omega", "--from", "7.23",
                                 "--to", "8.3", "--pd-depth", "0", "--curve", "fold", "--param2", "forcing.F0",
                                 "--from2", "400", "--to2", "600", "--format", "json"))
    curve = report["curves"][0]
    assert curve["kind"] == "fold" and curve["n"] == 1
    assert curve["stop"] == "left the box at forcing.F0 = 600; left the box at forcing.F0 = 400"
    for end in (curve["points"][0], curve["points"][-1]):
        sweep = json.loads(vibromap("orbit-diagram", "jobs/paper/table2.toml", "--set", f"forcing.F0={end['param2']}",
                                    "--param", "omega", "--from", "7.23", "--to", "8.5", "--steps", "128",
                                    "--transient", "600", "--keep", "2", "-q", "--format", "json"))
        up = sorted((s for s in sweep["steps"] if s["direction"] == "up"), key=lambda s: s["param"])
        off = next(i for i, s in enumerate(up) if abs(s["strobe_x1"][0] - s["strobe_x1"][1]) > 1e-4)
        assert off > 0
        assert up[off - 1]["param"] <= end["param"] < up[off]["param"], (end, up[off - 1]["param"], up[off]["param"])


def test_a_codim2_point_is_found_alike_on_both_its_curves(tmp_path):
    """With the doubled branch (--pd-depth 1), the fold curve and the period-doubling curve of
    Table 2's period-2 orbit cross over F0 in [400, 600] N: the fold curve sees det(M + I) change
    sign and the period-doubling curve det(M - I), each located by bisection along its own curve;
    both name the same point (measured 2026-11-26: omega 7.4147796061, F0 445.4172491 N, the two
    within 8e-11 rad/s and 1e-7 N)."""
    report = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--param", "omega", "--from", "7.23",
                                 "--to", "8.3", "--curve", "fold", "--curve", "period-doubling", "--param2",
                                 "forcing.F0", "--from2", "400", "--to2", "600", "--format", "json", "-o",
                                 tmp_path / "c.h5"))
    found = {x["kind"]: (x["param"], x["param2"], c["n"]) for c in report["curves"] for x in c["codim2"]}
    a, b = found["fold+period-doubling"], found["period-doubling+fold"]
    assert a[2] == b[2] == 2
    assert abs(a[0] - b[0]) < 1e-6 and abs(a[1] - b[1]) < 1e-4, (a, b)
    assert abs(a[0] - 7.41478) < 1e-4 and abs(a[1] - 445.417) < 1e-2
    with h5py.File(tmp_path / "c.h5", "r") as f:  # the file holds them too, kind as a string
        stored = {}
        for i, c in enumerate(report["curves"]):
            g = f[f"curve_{i}/codim2"]
            assert g.attrs.get("kind") is None and f[f"curve_{i}"].attrs["kind"] == c["kind"]
            for k, p, q in zip(g["kind"][()], g["param"][()], g["param2"][()]):
                stored[k.decode()] = (p, q)
        assert stored["fold+period-doubling"] == a[:2] and stored["period-doubling+fold"] == b[:2]


def test_the_grazing_curve_is_the_linear_closed_form():
    """The grazing of Table 2's contact-free orbit (followed down from omega = 11 rad/s) as a curve
    in (omega, F0) over [300, 700] N: without contact the system is linear, and the orbit touches
    where F0 |U1 - U2| = D, U = (K - omega^2 M + i omega C)^-1 (1, 0) the response of x1 and
    x2 - D per unit force (Table 2: m1 = 1000, m2 = 310 kg, omega1 = 6.283, omega2 = 3.606 rad/s,
    xi1 = xi2 = 0.01, D = 0.05 m). Every point at the scene's tolerance to 1e-7 (measured
    2026-11-26: 3.2e-10, 26 points)."""
    report = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--param", "omega", "--from", "11",
                                 "--to", "7.3", "--pd-depth", "0", "--curve", "grazing", "--param2", "F0",
                                 "--from2", "300", "--to2", "700", "--format", "json"))
    m1, m2, D = 1000.0, 310.0, 0.05
    k1, k2 = m1 * 6.283**2, m2 * 3.606**2
    c1, c2 = 2 * 0.01 * np.sqrt(m1 * k1), 2 * 0.01 * np.sqrt(m2 * k2)
    M, C = np.diag([m1, m2]), np.array([[c1 + c2, -c2], [-c2, c2]])
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    (curve,) = report["curves"]
    assert curve["kind"] == "grazing" and len(curve["points"]) > 10
    for p in curve["points"]:
        w, F0 = p["param"], p["param2"]
        U = np.linalg.solve(K - w * w * M + 1j * w * C, np.array([1.0, 0.0]))
        assert abs(F0 * abs(U[1] - U[0]) / D - 1.0) < 1e-7, p


def test_the_period_two_grazings_are_followed():
    """Table 2's period-2 orbit (doubled from the (1,1) branch over omega in [7.23, 12] rad/s)
    grazes near 7.4636 and 7.5831 rad/s where a further impact appears on an orbit with one
    (clearance_min < 0): both are followed as curves over F0 in [300, 700] N (none skipped), each
    said to separate 1 impact per cycle at lower F0 from 2 at higher (checked against shooting
    either side in tests/core/test_curve_continuation.cpp); the contact-free (1,1) grazing is the
    other kind."""
    report = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--param", "forcing.omega", "--from", "7.23",
                                 "--to", "12", "--curve", "grazing", "--param2", "forcing.F0", "--from2", "300",
                                 "--to2", "700", "--format", "json"))
    assert report["skipped"] == []
    curves = report["curves"]
    assert [c["n"] for c in curves] == [1, 2, 2]
    assert curves[0]["grazing"] == "a contact-free orbit touches: 1 at higher forcing.F0, 0 at lower forcing.F0"
    starts = []
    for c in curves[1:]:
        assert c["grazing"] == ("an impact appears on an orbit with 1 contact per cycle: 2 at higher forcing.F0, "
                                "1 at lower forcing.F0")
        assert c["stop"] == "left the box at forcing.F0 = 700; left the box at forcing.F0 = 300"
        assert max(p["residual"] for p in c["points"]) <= 1e-10
        starts.append(c["points"][c["start"]]["param"])
    assert abs(starts[0] - 7.4636) < 1e-4 and abs(starts[1] - 7.5831) < 1e-4, starts


def folds_at(F0):
    """The folds of Table 2's branch over omega in [6.6, 6.9] rad/s at force F0, followed from the
    orbit solved from rest at 6.6 rad/s."""
    branch = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--set", f"forcing.F0={F0!r}", "--set",
                                 "forcing.omega=6.6", "--param", "forcing.omega", "--from", "6.6", "--to", "6.9",
                                 "--pd-depth", "0", "--format", "json"))
    assert branch["stop"] == "reached the end of the interval"
    return sorted(b["param"] for b in branch["bifurcations"] if b["type"] == "fold")


def arm_at(points, F0):
    """omega where the run of points (walked from the cusp outwards) first crosses F0, linearly."""
    for a, b in zip(points, points[1:]):
        if (a["param2"] - F0) * (b["param2"] - F0) <= 0.0:
            w = (F0 - a["param2"]) / (b["param2"] - a["param2"])
            return a["param"] + w * (b["param"] - a["param"])
    raise AssertionError(f"the arm does not reach F0 = {F0}")


def test_the_cusp_of_the_folds_is_where_the_branch_gains_its_fold_pair():
    """Table 2's (1,1) branch swept down in omega from 8.3 rad/s has the folds 7.5758 and 8.2420
    rad/s at F0 = 500 N; their fold curve over F0 in [20, 600] N joins them through a cusp (the
    curve's projection turns back) near omega 6.73407 rad/s, F0 41.7331 N (measured 2026-11-26).
    Checked against plain one-parameter branches over omega in [6.6, 6.9]: 0.1 N below the cusp
    the branch has no fold, 0.1 N above it two, 3.7e-4 rad/s apart, each where an arm of the fold
    curve crosses that force to 1e-4 rad/s (the arms' points interpolated linearly; measured 3.5e-5
    and 6.3e-5)."""
    report = json.loads(vibromap("continue", "jobs/paper/table2.toml", "--set", "forcing.omega=8.3", "--param",
                                 "forcing.omega", "--from", "8.3", "--to", "6", "--pd-depth", "0", "--curve", "fold",
                                 "--param2", "forcing.F0", "--from2", "20", "--to2", "600", "--format", "json"))
    (curve,) = report["curves"]  # the two folds' starts lie on one curve
    cusps = [x for x in curve["codim2"] if x["kind"] == "cusp"]
    assert len(cusps) == 1, curve["codim2"]
    omega_c, F0_c = cusps[0]["param"], cusps[0]["param2"]
    assert abs(omega_c - 6.73407) < 1e-4 and abs(F0_c - 41.7331) < 1e-3, cusps
    points = curve["points"]
    low = min(range(len(points)), key=lambda i: points[i]["param2"])
    assert abs(points[low]["param2"] - F0_c) < 0.01  # the curve's lowest force is the cusp's
    assert folds_at(F0_c - 0.1) == []
    above = folds_at(F0_c + 0.1)
    assert len(above) == 2, above
    arms = sorted([arm_at(points[low::-1], F0_c + 0.1), arm_at(points[low:], F0_c + 0.1)])
    assert 0.0 < above[1] - above[0] < 1e-3 and abs(above[0] - omega_c) < 2e-3, above
    assert abs(above[0] - arms[0]) < 1e-4 and abs(above[1] - arms[1]) < 1e-4, (above, arms)
