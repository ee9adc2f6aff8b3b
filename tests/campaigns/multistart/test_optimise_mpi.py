"""End-to-end optimisations of the vibromap executable under mpiexec.

- a tiny scene (a 2 x 2 seeding [sweep] of m2 x omega2, 2 seeds x 2 algorithms) gives the same
  `best` list and the same evaluations on 1 and 2 ranks (wall times aside), and the starts
  really were spread over both ranks;
- the JSON `best` list: params in SI (k2 = m2 omega2^2 in N/m), k_con = T / T_con, a stable
  (1,1) no worse than the best seed, and `vibromap run` on the point alone confirms it;
- the HDF5 output: one group per start with every evaluation inside the box, the best one
  feasible, and the best point's trajectory file; vibromap-post plot_optimise draws them;
- bad optimisations end with one line and the documented exit code;
- min_soft_fraction at the bistable Table 2 point: kept by every feasible evaluation, the best
  point's re-check reported (JSON, HDF5) and equal to `run --census` with its size and seed, and
  a minimum above what the soft attractor holds leaves no feasible point.

Run by ctest (tests/optimise_tests.cmake), which sets VIBROMAP_EXE and VIBROMAP_MPIEXEC.
"""
import json
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, TABLE2_POINT, journal_records, kill_all  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
PLOT = [os.path.join(REPO, "postprocess", "vibromap-post"), "plot_optimise"]

OMEGA = 7.23  # forcing frequency of the scene defaults, rad/s
T = 2.0 * math.pi / OMEGA
AGREE_RTOL = 1e-6  # run at rtol 1e-10 against the re-solve at 1e-12

SCENE = """
[system]
m2 = 310.0
omega2 = 4.6

[contact]
E1 = 1e5
E2 = 1e5
R1 = 0.5
R2 = 0.5

[sweep]
m2 = { from = 200.0, to = 310.0, n = 2 }
omega2 = { from = 4.2, to = 5.0, n = 2 }
store = ["k_con", "T_con", "F_max"]

[optimise]
m2 = { min = 100.0, max = 310.0 }
omega2 = { min = 3.606, max = 5.646 }
algorithm = ["bobyqa", "gradient_projection"]
seeds = 2
max_evaluations = 60
best = 2
hertz_valid = false  # the tiny box lies beyond the Hertz limit: the farm's mechanics are tested here
"""


def write_scene(tmp_path, text=SCENE, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def optimise(ranks, scene, out, *extra, check=True):
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "optimise", str(scene), "-o", str(out), "-q", "--format", "json", *extra]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def without_times(value):
    """The value with every wall-time entry removed (they differ from run to run)."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if not k.endswith("wall_s")}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def test_best_point_does_not_depend_on_rank_count(tmp_path):
    scene = write_scene(tmp_path)
    one = json.loads(optimise(1, scene, tmp_path / "one.h5").stdout)
    two = json.loads(optimise(2, scene, tmp_path / "two.h5").stdout)
    assert one["ranks"] == 1 and two["ranks"] == 2
    assert len(one["best"]) >= 1
    assert without_times(one["best"]) == without_times(two["best"])
    starts_one = [without_times(s) for s in one["starts"]]
    starts_two = [without_times(s) for s in two["starts"]]
    for a, b in zip(starts_one, starts_two):
        a.pop("rank"), b.pop("rank")
    assert starts_one == starts_two
    assert {s["rank"] for s in two["starts"]} == {0, 1}  # both ranks ran starts
    with h5py.File(tmp_path / "one.h5", "r") as f1, h5py.File(tmp_path / "two.h5", "r") as f2:
        for name in f1["starts"]:
            for column in ("x", "objective", "violation", "feasible", "regime", "n", "k", "stable"):
                np.testing.assert_array_equal(f1["starts"][name][column][()], f2["starts"][name][column][()],
                                              err_msg=f"{name}/{column}")


def test_json_best_is_a_stable_one_one_that_run_confirms(tmp_path):
    scene = write_scene(tmp_path)
    report = json.loads(optimise(2, scene, tmp_path / "out.h5").stdout)
    assert report["objective"] == "min_k_con" and report["regime"] == "(1,1)"
    best = report["best"]
    k_cons = [b["k_con"] for b in best]
    assert k_cons == sorted(k_cons)  # best first
    top = best[0]
    assert set(top["params"]) >= {"m2", "k2", "E1", "E2", "R1", "R2", "omega2"}
    p = top["params"]
    assert 100.0 <= p["m2"] <= 310.0 and 3.606 <= p["omega2"] <= 5.646
    assert math.isclose(p["k2"], p["m2"] * p["omega2"] ** 2, rel_tol=1e-12)  # N/m
    assert (p["E1"], p["E2"], p["R1"], p["R2"]) == (1e5, 1e5, 0.5, 0.5)  # not free: the scene's
    assert top["regime"] == "(1,1)" and top["stable"] is True
    assert math.isclose(top["k_con"] * top["T_con"], T, rel_tol=1e-12)
    assert top["agree"] and top["shooting"]["regime"] == "(1,1)"
    assert math.isclose(top["k_con"], top["objective_found"], rel_tol=AGREE_RTOL)
    with h5py.File(tmp_path / "out_map.h5", "r") as f:  # the seeding sweep's map
        seed_best = np.nanmin(np.where(f["regime"][()] == 0, f["k_con"][()], np.nan))
    assert top["k_con"] < seed_best - 1e-3  # the optimiser improved on the best cell

    sets = [arg for s in top["set"] for arg in ("--set", s)]
    run = subprocess.run([EXE, "run", str(scene), *sets, "--format", "json"], env=ENV, capture_output=True,
                         text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    alone = json.loads(run.stdout)
    assert alone["regime"] == "(1,1)" and alone["stable"] is True
    assert math.isclose(alone["k_con"], top["k_con"], rel_tol=AGREE_RTOL)


def test_output_file_holds_every_start_and_evaluation(tmp_path):
    scene = write_scene(tmp_path)
    report = json.loads(optimise(2, scene, tmp_path / "out.h5").stdout)
    with h5py.File(tmp_path / "out.h5", "r") as f:
        assert f.attrs["variables"] == "m2 omega2"
        assert f.attrs["quantity"] == "k_con"
        bounds = f["bounds"][()]
        np.testing.assert_array_equal(bounds, [[100.0, 310.0], [3.606, 5.646]])
        assert sorted(f["starts"]) == ["000", "001", "002", "003"]
        for name, start in zip(sorted(f["starts"]), report["starts"]):
            g = f["starts"][name]
            x = g["x"][()]
            assert x.shape == (start["evaluations"], 2)
            assert ((x >= bounds[:, 0]) & (x <= bounds[:, 1])).all()
            best = int(g.attrs["best"])
            assert g["feasible"][best] == 1
            assert g["objective"][best] == start["best_objective"]
            feasible = g["feasible"][()] == 1
            assert g["objective"][()][feasible].min() == start["best_objective"]  # the best feasible, no other
            assert g.attrs["stop"] == start["stop"]
        assert f["best/00"].attrs["m2"] == report["best"][0]["params"]["m2"]
        assert f["best/00/integrate"].attrs["regime"] == "(1,1)"
        assert f["best/00/shooting"].attrs["k_con"] == report["best"][0]["shooting"]["k_con"]
        assert f.attrs["trajectory"] == "out_trajectory.h5"
    with h5py.File(tmp_path / "out_trajectory.h5", "r") as f:
        assert f.attrs["regime"] == "(1,1)"
        assert math.isclose(float(f.attrs["k_con"]), report["best"][0]["k_con"], rel_tol=1e-12)
        assert f["Fc"][()].max() > 0.0

    # The Python reader and figures on the C++ writer's files.
    env = dict(os.environ, MPLCONFIGDIR=str(tmp_path / "mpl"))
    plot = subprocess.run([*PLOT, str(tmp_path / "out.h5")], env=env, capture_output=True, text=True,
                          timeout=120)  # fmt: skip
    assert plot.returncode == 0, plot.stderr
    for suffix in ("convergence", "on_map", "best"):
        assert (tmp_path / f"out_{suffix}.png").stat().st_size > 15_000, suffix


def test_bad_optimisations_end_with_one_line(tmp_path):
    scene = write_scene(tmp_path)
    out = tmp_path / "out.h5"
    optimise(1, scene, out)
    again = optimise(2, scene, out, check=False)
    assert again.returncode == 2
    assert again.stderr.count("vibromap: error:") == 1
    assert "already exists; use --overwrite" in again.stderr
    replaced = optimise(2, scene, out, "--overwrite")
    assert json.loads(replaced.stdout)["best"]

    point = write_scene(tmp_path, "[system]\nm2 = 310.0\n", name="point.toml")
    proc = optimise(2, point, tmp_path / "none.h5", check=False)
    assert proc.returncode == 2
    assert proc.stderr.count("vibromap: error:") == 1
    assert "no [optimise] section" in proc.stderr
    assert not (tmp_path / "none.h5").exists()

    no_map = write_scene(tmp_path, SCENE.replace("[optimise]\n", '[optimise]\nmap = "missing.h5"\n'), name="m.toml")
    proc = optimise(2, no_map, tmp_path / "m.h5", check=False)
    assert proc.returncode == 4
    assert proc.stderr.count("vibromap: error:") == 1
    assert "missing.h5" in proc.stderr

    far = write_scene(tmp_path, SCENE.replace('seeds = 2\n', 'seeds = 2\nregime = "(3,2)"\n'), name="far.toml")
    proc = optimise(2, far, tmp_path / "far.h5", check=False)
    assert proc.returncode == 2
    assert proc.stderr.count("vibromap: error:") == 1
    assert "no cell of the map keeps the regime (3,2)" in proc.stderr


def test_killed_optimisation_resumes_to_the_same_best_point(tmp_path):
    """kill -9 of mpiexec and every rank once some starts are in the journal: --resume runs only
    the other starts and ends with the same starts and best points as an uninterrupted run."""
    text = SCENE.replace("seeds = 2", "seeds = 4").replace("max_evaluations = 60", "max_evaluations = 120")
    scene = write_scene(tmp_path, text)
    reference = json.loads(optimise(2, scene, tmp_path / "ref.h5").stdout)
    total = len(reference["starts"])

    out = tmp_path / "killed.h5"
    journal = tmp_path / "killed.h5.journal"
    cmd = [MPIEXEC, "-n", "2", EXE, "optimise", str(scene), "-o", str(out), "-q"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None and journal_records(journal) < 2:
        time.sleep(0.02)
    assert proc.poll() is None, "the optimisation finished before it could be killed; make it longer"
    kill_all(proc.pid)
    proc.wait()
    kept = journal_records(journal)
    assert 2 <= kept < total and not out.exists()

    refused = optimise(2, scene, out, check=False)  # neither --resume nor --overwrite
    assert refused.returncode == 2 and "(an unfinished run of this output left it); use --resume to continue it" in refused.stderr

    resumed = json.loads(optimise(2, scene, out, "--resume").stdout)
    assert resumed["starts_resumed"] == kept
    assert resumed["sweep_cells_computed"] == 0  # the seeding map was complete: reused
    strip = lambda starts: [{k: v for k, v in without_times(s).items() if k != "rank"} for s in starts]
    assert strip(resumed["starts"]) == strip(reference["starts"])
    assert without_times(resumed["best"]) == without_times(reference["best"])
    assert not journal.exists()  # removed once the output is written


def test_a_seeding_map_that_cannot_seed_is_kept_and_said_so(tmp_path):
    """No cell of the seeding sweep holds the kept regime: exit 2, and the line says the map it
    made is kept (before, it said "nothing written" after writing it)."""
    scene = write_scene(tmp_path, SCENE.replace("[optimise]\n", '[optimise]\nregime = "(9,9)"\n'))
    proc = optimise(2, scene, tmp_path / "out.h5", check=False)
    assert proc.returncode == 2
    assert proc.stderr.count("vibromap: error:") == 1
    assert f"the seeding map {tmp_path / 'out_map.h5'} is kept for the next run" in proc.stderr
    with h5py.File(tmp_path / "out_map.h5", "r") as f:
        assert f["done"][()].all()
    assert not (tmp_path / "out.h5").exists()


# Robust softness at the bistable Table 2 point ((1,1) soft in about 56 % of the basin, (3,3)
# beyond Hertz's range): a census of 8 states per feasible point, the best point re-checked with
# max(32, 4 x 8) = 32 other states (seed 1 + 1).
ROBUST = TABLE2_POINT + """
[census]
initial_conditions = 8

[optimise]
E2 = { min = 8e5, max = 1.2e6, scale = "log" }
max_evaluations = 8
best = 1
min_soft_fraction = 0.3
soft_check_initial_conditions = 32
"""


def test_min_soft_fraction_is_kept_reported_and_rechecked(tmp_path):
    scene = write_scene(tmp_path, ROBUST)
    report = json.loads(optimise(2, scene, tmp_path / "out.h5").stdout)
    assert report["min_soft_fraction"] == 0.3 and report["soft_check_initial_conditions"] == 32
    top = report["best"][0]
    assert top["regime"] == "(1,1)" and top["soft_fraction"] >= 0.3  # the optimiser's census there
    check = top["soft_check"]
    assert check["status"] == "ok" and check["initial_conditions"] == 32 and check["seed"] == 2
    p = check["soft_fraction"]
    assert math.isclose(check["soft_fraction_stderr"], math.sqrt(p * (1 - p) / 32), rel_tol=1e-12)
    assert math.isclose(check["threshold"], 0.3 - 3 * check["soft_fraction_stderr"], rel_tol=1e-12)
    assert check["passed"] == (p >= check["threshold"])
    assert 0.561 - 3 * 0.0877 <= p <= 0.561 + 3 * 0.0877  # the (1,1)'s brute-force basin, 1,000 states
    orbit = check["attractors"][check["orbit_attractor"]]  # the optimised orbit is the soft (1,1)
    assert orbit["regime"] == "(1,1)" and orbit["soft"] and orbit["fraction"] == check["orbit_fraction"]
    assert math.isclose(orbit["k_con"], top["k_con"], rel_tol=AGREE_RTOL)

    # `vibromap run --census` at the point with the re-check's size and seed: the same fraction.
    sets = [arg for s in top["set"] for arg in ("--set", s)]
    run = subprocess.run([EXE, "run", str(scene), *sets, "--census", "--format", "json", "--set",
                          "census.initial_conditions=32", "--set", "census.seed=2"],
                         env=ENV, capture_output=True, text=True, timeout=120)  # fmt: skip
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["soft_fraction"] == p

    with h5py.File(tmp_path / "out.h5", "r") as f:
        assert f.attrs["min_soft_fraction"] == 0.3 and f.attrs["soft_check_initial_conditions"] == 32
        assert f.attrs["measures"].split()[-1] == "soft_fraction"
        g = f["starts/000"]
        soft, feasible = g["soft_fraction"][()], g["feasible"][()] == 1
        assert feasible.any() and (soft[feasible] >= 0.3).all()
        assert f["best/00"].attrs["soft_fraction"] == top["soft_fraction"]
        c = f["best/00/soft_check"]
        assert c.attrs["soft_fraction"] == p and c.attrs["passed"] == int(check["passed"])
        assert c.attrs["initial_conditions"] == 32
        states = c.attrs["unresolved"] + c.attrs["unlisted"]
        assert math.isclose(float(c["fraction"][()].sum()) + states / 32, 1.0, rel_tol=1e-12)
    env = dict(os.environ, MPLCONFIGDIR=str(tmp_path / "mpl"))
    plot = subprocess.run([*PLOT, str(tmp_path / "out.h5")], env=env, capture_output=True, text=True,
                          timeout=120)  # fmt: skip
    assert plot.returncode == 0, plot.stderr

    # 0.9 is more than the (1,1) holds anywhere in this box: no feasible point, each census said so.
    strict = json.loads(optimise(2, scene, tmp_path / "strict.h5", "--set", "optimise.min_soft_fraction=0.9").stdout)
    assert strict["best"] == [] and all(s["best_objective"] is None for s in strict["starts"])
    with h5py.File(tmp_path / "strict.h5", "r") as f:
        soft = f["starts/000/soft_fraction"][()]
        assert np.isfinite(soft).any() and (soft[np.isfinite(soft)] < 0.9).all()
        assert (f["starts/000/violation"][()] > 0).all()
