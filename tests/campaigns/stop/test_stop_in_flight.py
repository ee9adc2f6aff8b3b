"""A stop signal ends a campaign even while one item runs for hours (issue #28): the core's
integrators poll the stop flag inside an item, the item in flight is abandoned (not recorded),
and the run checkpoints and exits 3 within moments, on 1 and 2 ranks.

Every item here would run for hours: an undamped chatter from v2 = 5 m/s never settles, and
its budgets (10^10 steps, 10^8 periods) are far beyond the test. Before the fix, sweep,
optimise, basins and orbit-diagram went on with the item in flight and ignored SIGTERM (an
optimise with omega1 = 2147483647 left its journal and lock after `kill`).

Run by ctest (tests/campaigns/campaign_tests.cmake)."""
import os
import signal
import subprocess
import sys
import time

import h5py
import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, FOREVER, MPIEXEC, journal_records  # noqa: E402


SWEEP = FOREVER + """
[sweep]
m2 = { values = [100.0, 110.0] }
progress_interval = 0.2
"""

OPTIMISE = FOREVER + """
[optimise]
m2 = { min = 100.0, max = 310.0 }
seeds = 1
max_evaluations = 5
"""

# Starts of moments, then a re-solve of the best point that would take hours: its soft fraction
# re-checked by a census of 10^6 initial states (the Table 2 point, where (1,1) is soft).
VERIFY_FOREVER = """
[system]
m2 = 310.0
omega2 = 3.606

[contact]
E1 = 1.4e10
E2 = 1.0e6
R1 = 2.0
R2 = 2.0

[census]
initial_conditions = 4

[optimise]
m2 = { min = 305.0, max = 310.0 }
algorithm = "bobyqa"
seeds = 1
max_evaluations = 3
min_soft_fraction = 0.5
soft_check_initial_conditions = 1000000
"""

# The longest a stop may take here: the item in flight would take hours, so anything that ends
# within this ends because the signal was seen (MPI start-up and the final checkpoint included).
STOP_TIMEOUT = 60


def write(tmp_path, text, name):
    path = tmp_path / name
    path.write_text(text)
    return path


def signal_and_wait(proc, sig, what):
    """Sends `sig` to `proc` and waits at most STOP_TIMEOUT s for it to end; returns its stderr."""
    proc.send_signal(sig)
    try:
        return proc.communicate(timeout=STOP_TIMEOUT)[1]
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        raise AssertionError(f"{what} went on {STOP_TIMEOUT} s after {sig.name}")


def stop(cmd, sig, started=3.0):
    """Starts cmd, lets it compute for `started` s, sends `sig`; returns (exit code, stderr, s to stop)."""
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(started)
    assert proc.poll() is None, proc.communicate()
    t0 = time.time()
    err = signal_and_wait(proc, sig, f"{cmd[0]} {cmd[1]}")
    return proc.returncode, err, time.time() - t0


def test_a_sweep_stops_in_its_first_cell(tmp_path):
    scene = write(tmp_path, SWEEP, "sweep.toml")
    for n, sig in ((1, signal.SIGTERM), (2, signal.SIGUSR1)):
        out = tmp_path / f"map{n}.h5"
        cmd = [EXE, "sweep", str(scene), "-o", str(out), "-q"]
        if n > 1:
            cmd = [MPIEXEC, "-n", str(n)] + cmd
        rc, err, _ = stop(cmd, sig)
        assert rc == 3, err
        assert f"stopped by {signal.Signals(sig).name} after a checkpoint" in err
        with h5py.File(out, "r") as f:  # the cells in flight were abandoned, not recorded
            assert f["done"][()].sum() == 0
        assert not (tmp_path / f"map{n}.h5.lock").exists()


def test_an_optimise_start_stops_and_keeps_its_journal(tmp_path):
    scene = write(tmp_path, OPTIMISE, "opt.toml")
    out = tmp_path / "opt.h5"
    rc, err, _ = stop([EXE, "optimise", str(scene), "-o", str(out), "-q"], signal.SIGTERM)
    assert rc == 3, err
    assert "stopped by SIGTERM" in err
    assert (tmp_path / "opt.h5.journal").exists(), "the journal stays for --resume"
    assert not (tmp_path / "opt.h5.lock").exists()
    assert not out.exists()


def test_basins_stop_in_their_first_pixels(tmp_path):
    scene = write(tmp_path, FOREVER, "basins.toml")
    out = tmp_path / "b.h5"
    rc, err, _ = stop([EXE, "basins", str(scene), "--grid", "2x2", "-o", str(out), "-q"], signal.SIGTERM)
    assert rc == 3, err
    assert not (tmp_path / "b.h5.lock").exists()


def test_an_orbit_diagram_stops_in_its_transient(tmp_path):
    for n, sig in ((1, signal.SIGTERM), (2, signal.SIGUSR1)):
        cmd = [EXE, "orbit-diagram", os.path.abspath("jobs/paper/table1.toml"), "-p", "omega", "--from", "7",
               "--to", "7.5", "--steps", "2", "--transient", "100000000", "-q"]
        if n > 1:
            cmd = [MPIEXEC, "-n", str(n)] + cmd
        rc, err, _ = stop(cmd, sig)
        assert rc == 3, err


@pytest.mark.parametrize("phase, sig", [("starts", signal.SIGINT), ("verification", signal.SIGINT),
                                        ("verification", signal.SIGUSR1)])
def test_ctrl_c_to_mpiexec_stops_an_optimise_on_two_ranks(tmp_path, phase, sig):
    """Ctrl-C (SIGINT) to `mpiexec -n 2 vibromap optimise SCENE -q` (#29 item 4), in the starts and
    while rank 0 re-solves the best point: the ranks stop, rank 0 says so despite -q, no lock
    file is left and the journal keeps the finished starts. mpiexec passes SIGINT on as SIGTERM
    a second later, SIGKILL a second after that, and exits 1 whatever the ranks return; SIGUSR1
    it forwards, and returns the ranks' 3 (docs/guide-optimise.md). Before the fix the re-solves
    did not poll the stop flag: SIGKILL ended them, with no line and both lock files left."""
    scene = write(tmp_path, OPTIMISE if phase == "starts" else VERIFY_FOREVER, "opt.toml")
    out, journal = tmp_path / "opt.h5", tmp_path / "opt.h5.journal"
    proc = subprocess.Popen([MPIEXEC, "-n", "2", EXE, "optimise", str(scene), "-o", str(out), "-q"], env=ENV,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if phase == "starts":
        time.sleep(3.0)  # the start in flight would take hours
    else:  # the one start is in the journal: rank 0 is re-solving (for hours)
        deadline = time.time() + 120
        while time.time() < deadline and proc.poll() is None and journal_records(journal) < 1:
            time.sleep(0.02)
    assert proc.poll() is None, proc.communicate()
    err = signal_and_wait(proc, sig, "mpiexec")
    forwarded = "SIGUSR1" if sig == signal.SIGUSR1 else "SIGTERM"
    assert proc.returncode == (3 if sig == signal.SIGUSR1 else 1), err
    assert (f"vibromap: stopped by {forwarded} after a checkpoint: {journal} holds the finished starts; run the same "
            "command with --resume to go on") in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["opt.h5.journal", "opt.toml"]  # no lock, no output
    assert journal_records(journal) == (0 if phase == "starts" else 1)
