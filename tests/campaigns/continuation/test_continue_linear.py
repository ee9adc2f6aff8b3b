"""`vibromap continue` from the command line against the closed-form linear response (issue #31,
item 5): Table 2's system without contact (system.D = 10 m, beyond any motion) is linear, its
periodic response at omega is x1 = Re(Q1 e^(i omega t)), x2 = D + Re(Q2 e^(i omega t)) with
(Q1, Q2) = (K - omega^2 M + i omega C)^-1 (lambda F0 e^(i phi0), 0), so over a cycle
x1_max = |Q1| and clearance_min = min(x2 - x1) = D - |Q2 - Q1| (tests/core/test_continuation.cpp
checks the same in C++). The continuation's corrector stops at the scene's Newton tolerance
(analysis.newton_tol; 0: 10 solver.rtol, 1e-9 at the defaults); each reported point then takes one
more Newton step at its own parameter before its extremes are measured, so the extremes are as
exact as the integration (at the defaults the corrected state alone was 1.8e-7 off).
"""
import json
import os
import subprocess
import tomllib

import numpy as np

EXE = os.environ.get("VIBROMAP_EXE", "build/vibromap")
SCENE = "jobs/paper/table2.toml"
D = 10.0  # m
ARGS = ["continue", SCENE, "--set", f"system.D={D:g}", "--param", "forcing.omega", "--from", "2", "--to", "12",
        "--format", "json"]


def closed_form(omega):
    """(|Q1|, |Q2 - Q1|) of Table 2's linear response at omega (the scene's values; c = 2 xi m omega_i)."""
    with open(SCENE, "rb") as f:
        scene = tomllib.load(f)
    s, forcing = scene["system"], scene["forcing"]
    m1, m2 = s["m1"], s["m2"]
    k1, k2 = m1 * s["omega1"] ** 2, m2 * s["omega2"] ** 2
    c1, c2 = 2.0 * s["xi1"] * np.sqrt(m1 * k1), 2.0 * s["xi2"] * np.sqrt(m2 * k2)
    M = np.diag([m1, m2])
    C = np.array([[c1 + c2, -c2], [-c2, c2]])
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    f = np.array([forcing["lambda"] * forcing["F0"] * np.exp(1j * forcing["phi0"]), 0.0])
    Q = np.linalg.solve(K - omega**2 * M + 1j * omega * C, f)
    return abs(Q[0]), abs(Q[1] - Q[0])


def branch(*sets):
    result = subprocess.run([EXE] + ARGS + [a for s in sets for a in ("--set", s)], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def worst_errors(data):
    """The largest error of x1_max and of clearance_min over the branch's points, relative to the
    amplitudes |Q1| and |Q2 - Q1| (relative to clearance_min itself, ~10 m, it would be ~20 times
    smaller)."""
    x1, clearance = 0.0, 0.0
    for p in data["points"]:
        a1, a12 = closed_form(p["param"])
        x1 = max(x1, abs(p["x1_max"] - a1) / a1)
        clearance = max(clearance, abs(p["clearance_min"] - (D - a12)) / a12)
    return x1, clearance


def linear_branch_errors(*sets):
    data = branch(*sets)
    points = data["points"]
    assert data["stop"] == "reached the end of the interval" and data["bifurcations"] == []
    assert len(points) > 50 and points[0]["param"] == 2.0 and points[-1]["param"] == 12.0
    assert all(p["impacts"] == 0 and p["stable"] for p in points)
    x1, clearance = worst_errors(data)
    print(f"{sets or 'defaults'}: {len(points)} points; worst relative error x1_max {x1:.2e}, "
          f"clearance_min {clearance:.2e}")
    return x1, clearance


def test_the_linear_branch_is_the_closed_form_to_1e_8_at_the_defaults():
    x1, clearance = linear_branch_errors()
    assert x1 <= 1e-8
    assert clearance <= 1e-8


def test_the_linear_branch_is_the_closed_form_to_1e_8_at_the_scenes_own_tolerances():
    """A tighter Newton tolerance, or a tighter integration (whose 10 rtol the corrector then
    uses), keeps the branch on the closed form."""
    for sets in (("analysis.newton_tol=1e-11",), ("solver.rtol=1e-12",)):
        x1, clearance = linear_branch_errors(*sets)
        assert x1 <= 1e-8 and clearance <= 1e-8, sets


def test_a_newton_tolerance_continuation_cannot_use_is_refused_in_one_line():
    result = subprocess.run([EXE] + ARGS + ["--set", "analysis.newton_tol=0.05"], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.splitlines() == [
        f"vibromap: error: {SCENE}: continue needs a Newton tolerance below 0.01; analysis.newton_tol gives 0.05 "
        "(when 0: 10 solver.rtol)"]
