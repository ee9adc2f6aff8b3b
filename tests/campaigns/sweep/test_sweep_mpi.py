"""End-to-end sweeps of the vibromap executable under mpiexec.

- the map does not depend on the number of ranks (1, 2, 3): every dataset but wall_s is identical;
- a sweep killed with SIGKILL (every rank, as a cluster's time limit does) leaves a map that
  h5py opens, and --resume finishes it with no cell lost or recomputed beyond the checkpoint,
  giving the same map as an uninterrupted run;
- bad sweeps end with exit code 2 and one line.

Run by ctest (tests/sweep_tests.cmake), which sets VIBROMAP_EXE and VIBROMAP_MPIEXEC.
"""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np
import pytest

import pathlib

REPO = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, kill_all, slow_scene, wait_for_cells_done  # noqa: E402

def write_scene(tmp_path, n1=4, n2=3, checkpoint=60.0, name="scene.toml"):
    path = tmp_path / name
    path.write_text(slow_scene(n1, n2, checkpoint))
    return path


def sweep(ranks, scene, out, *extra, check=True):
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "sweep", str(scene), "-o", str(out), "--quiet", *extra]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def datasets(path):
    with h5py.File(path, "r") as f:
        return {name: f[name][()] for name in f if isinstance(f[name], h5py.Dataset)}


def assert_same_map(a, b):
    da, db = datasets(a), datasets(b)
    assert sorted(da) == sorted(db)
    for name in da:
        if name == "wall_s":
            continue
        np.testing.assert_array_equal(da[name], db[name], err_msg=name)


def test_map_does_not_depend_on_rank_count(tmp_path):
    scene = write_scene(tmp_path)
    maps = []
    for ranks in (1, 2, 3):
        out = tmp_path / f"map{ranks}.h5"
        sweep(ranks, scene, out)
        maps.append(out)
    with h5py.File(maps[0], "r") as f:
        assert f["done"][()].all()
        assert int(f.attrs["cells_done"]) == 12
        assert f["regime"].shape == (4, 3)
    for other in maps[1:]:
        assert_same_map(maps[0], other)
    with h5py.File(maps[2], "r") as f:
        assert int(f.attrs["ranks"]) == 3


def test_the_report_gives_each_kind_of_cells_speed(tmp_path):
    """The report's classes (JSON) and speed line (table): per regime kind, the cells solved and
    their summed solve time, against the map's own regime and wall_s (issue 42)."""
    scene = write_scene(tmp_path)
    out, table = tmp_path / "map.h5", tmp_path / "table.h5"
    report = json.loads(sweep(2, scene, out, "--format", "json").stdout)
    expected = {}
    with h5py.File(out, "r") as f:
        regime, wall = f["regime"][()], f["wall_s"][()]
        meanings = f["regime"].attrs["flag_meanings"]
        meanings = (meanings.decode() if isinstance(meanings, bytes) else meanings).split()
        for code, name in zip(f["regime"].attrs["flag_values"], meanings):
            solved = (regime == code) & (wall > 0)
            if solved.any():
                expected[name.replace("_", "-")] = (int(solved.sum()), float(wall[solved].sum()))
    assert expected and sorted(report["classes"]) == sorted(expected)
    for kind, (cells, seconds) in expected.items():
        got = report["classes"][kind]
        assert got["cells"] == cells, kind
        assert got["solve_s"] == pytest.approx(seconds, rel=1e-9), kind
        assert got["cells_per_s"] == pytest.approx(cells / seconds, rel=1e-9), kind
    text = subprocess.run([EXE, "sweep", str(scene), "-o", str(table)], env=ENV, capture_output=True, text=True,
                          timeout=600).stdout
    speed = [line for line in text.splitlines() if line.startswith("speed ")]
    assert len(speed) == 1, text
    for kind in expected:
        assert f" {kind} " in speed[0] and "cells/s" in speed[0], speed[0]


def test_killed_sweep_resumes_to_the_same_map(tmp_path):
    scene = write_scene(tmp_path, n1=8, n2=6, checkpoint=0.3)
    reference = tmp_path / "reference.h5"
    sweep(2, scene, reference)

    out = tmp_path / "killed.h5"
    cmd = [MPIEXEC, "-n", "2", EXE, "sweep", str(scene), "-o", str(out), "--quiet"]
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_cells_done(proc, out, 5)
    assert proc.poll() is None, "the sweep finished before it could be killed; make it longer"
    kill_all(proc.pid)
    proc.wait()

    with h5py.File(out, "r") as f:  # the killed run's map opens and is consistent
        done = f["done"][()]
        assert int(f.attrs["complete"]) == 0
        assert 0 < done.sum() < done.size
        assert (f["regime"][()][done == 0] == -1).all()
        assert np.isnan(f["T_con"][()][done == 0]).all()
        before = int(done.sum())

    proc = sweep(2, scene, out, "--resume", "--format", "json")
    report = json.loads(proc.stdout)
    assert report["cells_resumed"] == before
    assert report["cells_computed"] == 48 - before
    assert_same_map(reference, out)


def test_resume_takes_the_same_scene_written_otherwise(tmp_path):
    scene = write_scene(tmp_path)
    out = tmp_path / "map.h5"
    sweep(1, scene, out)
    same = tmp_path / "same.toml"  # 310 for 310.0, comments, other key order and intervals
    same.write_text("# the same run\n" + scene.read_text()
                    .replace("m2 = 310.0\nomega2 = 3.606", "omega2 = 3.606  # rad/s\nm2 = 310")
                    .replace("progress_interval = 0.5", "progress_interval = 2"))
    report = json.loads(sweep(1, same, out, "--resume", "--format", "json").stdout)
    assert report["cells_resumed"] == 12 and report["cells_computed"] == 0


def test_bad_sweeps_exit_2_with_one_line(tmp_path):
    scene = write_scene(tmp_path)
    out = tmp_path / "map.h5"
    sweep(1, scene, out)
    again = sweep(2, scene, out, check=False)
    assert again.returncode == 2
    assert again.stderr.count("vibromap: error:") == 1
    assert "already exists" in again.stderr

    other = write_scene(tmp_path, n1=5, name="other.toml")
    resumed = sweep(1, other, out, "--resume", check=False)
    assert resumed.returncode == 2
    assert "made by another run than" in resumed.stderr
    assert "sweep.axis.0 (contact.E1 log [20000, " in resumed.stderr  # the differing key, named

    heavier = tmp_path / "heavier.toml"
    heavier.write_text(scene.read_text().replace("m2 = 310.0", "m2 = 320.0"))
    resumed = sweep(1, heavier, out, "--resume", check=False)
    assert resumed.returncode == 2
    assert "system.m2 (310 in the file, 320 in the scene)" in resumed.stderr

    no_sweep = tmp_path / "point.toml"
    no_sweep.write_text("[system]\nm2 = 310.0\n")
    proc = sweep(2, no_sweep, tmp_path / "none.h5", check=False)
    assert proc.returncode == 2
    assert "no [sweep] section" in proc.stderr
    assert not (tmp_path / "none.h5").exists()


def stopped_cells(stderr):
    """The cell count of the 'stopped by SIG...: FILE holds N of M cells' line."""
    line = next(l for l in stderr.splitlines() if "stopped by" in l)
    words = line.split()
    return int(words[words.index("holds") + 1])


def start_and_signal(cmd, sig, cells=5):
    """Starts cmd (a sweep with progress lines on stderr), sends `sig` once a progress line shows
    at least `cells` cells done, and returns (exit code, stderr)."""
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = []
    for line in proc.stderr:
        lines.append(line)
        if line.startswith("sweep: ") and int(line.split()[1].split("/")[0]) >= cells:
            proc.send_signal(sig)
            break
    lines.extend(proc.stderr)
    proc.wait(timeout=120)
    return proc.returncode, "".join(lines)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGUSR1])
def test_a_signal_stops_the_sweep_with_a_checkpoint_and_exit_3(tmp_path, sig):
    """One process, no mpiexec: each stop signal ends the run with the cells computed so far in
    the map (checkpoint_interval is long, so only the final checkpoint can hold them), exit 3,
    and --resume finishes the map."""
    scene = write_scene(tmp_path, n1=8, n2=6, checkpoint=600.0)
    out = tmp_path / "stopped.h5"
    rc, stderr = start_and_signal([EXE, "sweep", str(scene), "-o", str(out)], sig)
    assert rc == 3, stderr
    assert stderr.count("vibromap: stopped by " + signal.Signals(sig).name) == 1
    held = stopped_cells(stderr)
    with h5py.File(out, "r") as f:
        assert int(f["done"][()].sum()) == held
    assert 5 <= held < 48
    proc = sweep(1, scene, out, "--resume", "--format", "json")
    assert json.loads(proc.stdout)["cells_resumed"] == held


def test_a_signal_in_the_first_instant_is_honoured(tmp_path):
    """SIGTERM as soon as the process catches it, while MPI and the scene are still being set up:
    the run still ends with exit 3 and its line, not killed without a word."""
    scene = write_scene(tmp_path, n1=8, n2=6)
    out = tmp_path / "early.h5"
    proc = subprocess.Popen([EXE, "sweep", str(scene), "-o", str(out), "--quiet"], env=ENV,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # The first instant: as soon as the handlers are in (main's first statement; before that the
    # dynamic loader is still at work, and how long it takes depends on the machine's load).
    catches_sigterm = lambda: int(next((line.split()[1] for line in open(f"/proc/{proc.pid}/status")
                                        if line.startswith("SigCgt:")), "0"), 16) >> (signal.SIGTERM - 1) & 1
    deadline = time.monotonic() + 60
    while not catches_sigterm() and time.monotonic() < deadline:
        time.sleep(0.001)
    proc.send_signal(signal.SIGTERM)
    _, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 3, stderr
    assert "vibromap: stopped by SIGTERM" in stderr


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGUSR1])
def test_a_signal_to_mpiexec_checkpoints_every_rank(tmp_path, sig):
    """SIGTERM or SIGUSR1 to mpiexec (what Ctrl-C, scancel or a batch system's warning does):
    mpiexec passes a signal to the ranks, which store what they computed, write the final
    checkpoint and say so; --resume finishes the map to the uninterrupted one."""
    scene = write_scene(tmp_path, n1=12, n2=8, checkpoint=600.0)
    reference = tmp_path / "reference.h5"
    sweep(2, scene, reference)
    out = tmp_path / "stopped.h5"
    rc, stderr = start_and_signal([MPIEXEC, "-n", "2", EXE, "sweep", str(scene), "-o", str(out)], sig)
    assert "vibromap: stopped by" in stderr, stderr
    if sig == signal.SIGUSR1:
        assert rc == 3  # mpiexec forwards SIGUSR1 and returns the ranks' code
    held = stopped_cells(stderr)
    with h5py.File(out, "r") as f:
        assert int(f["done"][()].sum()) == held
    assert 5 <= held < 96
    sweep(2, scene, out, "--resume")
    assert_same_map(reference, out)


def test_a_frequency_response_map_over_forcing_keys(tmp_path):
    """forcing.omega x forcing.F0 axes (any numeric key): the map's coordinates carry their
    units (rad/s, N), long names and keys, and the regime picture is drawn over them."""
    text = (REPO / "jobs" / "demo" / "frequency_response.toml").read_text()
    text = text.replace("n = 46", "n = 5").replace("n = 20", "n = 3")
    path = tmp_path / "fr.toml"
    path.write_text(text)
    out = tmp_path / "fr.h5"
    sweep(2, path, out)
    with h5py.File(out, "r") as f:
        assert f["regime"].shape == (3, 5)  # rows F0, columns omega
        assert f["omega"].attrs["units"] == "rad/s" and f["omega"].attrs["key"] == "forcing.omega"
        assert f["F0"].attrs["units"] == "N" and f["F0"].attrs["key"] == "forcing.F0"
        assert f["omega"].attrs["long_name"].startswith("forcing frequency")
        np.testing.assert_array_equal(f["omega"][()], [3.0, 5.25, 7.5, 9.75, 12.0])
        assert f["done"][()].all()
    sys.path.insert(0, str(REPO / "postprocess"))
    import matplotlib
    matplotlib.use("Agg")
    from vibromap.plot import _regime_map as plot_regime_map
    from vibromap import _io as vibromap_h5
    m = vibromap_h5.read_map(str(out))
    sl = plot_regime_map.choose_slice(m, "forcing.omega", "forcing.F0", {})
    fig = plot_regime_map.plot(m, sl)
    ax = fig.axes[0]
    assert ax.get_xlabel().startswith("omega (forcing frequency") and ax.get_xlabel().endswith("rad/s")
    assert ax.get_ylabel().startswith("F0 (force amplitude") and ax.get_ylabel().endswith(", N")
    assert ax.get_yscale() == "log"
