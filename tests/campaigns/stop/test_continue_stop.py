"""`vibromap continue` stopped by a signal: the branch (or curve) being followed ends before its
next point with stop "stopped by SIGNAL", the points found are printed and written whole (-o),
stderr says so in one line and the exit code is 3, the code of every interrupted campaign
(docs/guide-continuation.md#stopping-a-continuation). Before, continue had the default actions:
SIGTERM or SIGINT killed it at once with nothing printed and nothing written.

Every run here would take hours: Table 2's branch over omega in [3, 12] rad/s in steps of at
most 1e-4 (scaled arclength: about 2200 points a second here, up to --max-points 10^6).

Run by ctest (tests/campaigns/campaign_tests.cmake)."""
import json
import os
import signal
import subprocess
import sys
import time

import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, FOREVER  # noqa: E402

h5py = pytest.importorskip("h5py")

LONG = ["continue", "jobs/paper/table2.toml", "--param", "forcing.omega", "--from", "3", "--to", "12",
        "--ds-max", "1e-4", "--max-points", "1000000", "--pd-depth", "0"]
STOP_TIMEOUT = 60  # the run would take hours: ending within this is the signal's doing


def stopped(args, sig, tmp_path):
    """Runs vibromap ARGS for 3 s, sends `sig`; returns (exit code, stdout, stderr)."""
    proc = subprocess.Popen([EXE, *map(str, args)], env=ENV, cwd=os.getcwd(), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    time.sleep(3.0)
    assert proc.poll() is None, proc.communicate()
    proc.send_signal(sig)
    try:
        out, err = proc.communicate(timeout=STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        raise AssertionError(f"continue went on {STOP_TIMEOUT} s after {sig.name}")
    return proc.returncode, out, err


def test_a_branch_stops_with_its_points_written(tmp_path):
    path = tmp_path / "branch.h5"
    rc, out, err = stopped(LONG + ["-o", path, "--format", "json"], signal.SIGTERM, tmp_path)
    assert rc == 3, err
    report = json.loads(out)
    assert report["stop"] == "stopped by SIGTERM"
    params = [p["param"] for p in report["points"]]
    assert len(params) >= 1 and params[0] == 3.0
    assert err == (f"vibromap: stopped by SIGTERM after {len(params)} points: the output above and {path} hold the "
                   "continuation so far (stop: 'stopped by SIGTERM'); continue has no --resume: run it again to go on\n")
    with h5py.File(path, "r") as f:
        assert f.attrs["stop"] == "stopped by SIGTERM"
        assert list(f["param"][()]) == params
    assert sorted(p.name for p in tmp_path.iterdir()) == ["branch.h5"]  # no temporary or lock file left


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGUSR1])
def test_a_curve_run_stops_in_its_branch_without_a_curve(tmp_path, sig):
    args = LONG + ["--curve", "fold", "--param2", "forcing.F0", "--from2", "300", "--to2", "700"]
    rc, out, err = stopped(args, sig, tmp_path)
    name = signal.Signals(sig).name
    assert rc == 3, err
    points = int(out.split("\npoints         ")[1].split(";")[0])
    assert f"\npoints         {points}; stopped by {name}\n" in out
    assert "\ncurves         0 in (forcing.omega, forcing.F0)" in out
    assert err == (f"vibromap: stopped by {name} after {points} points, before the first curve: the output above "
                   f"holds the continuation so far (stop: 'stopped by {name}'); continue has no --resume: run it "
                   "again to go on\n")
    assert list(tmp_path.iterdir()) == []


def test_a_curve_run_stopped_before_its_first_curve_writes_the_branch_so_far(tmp_path):
    # The file the message names holds what was found: the branch, as a branch file (a curve file
    # would hold nothing), point for point what stdout gives.
    path = tmp_path / "c.h5"
    args = LONG + ["--curve", "fold", "--param2", "forcing.F0", "--from2", "300", "--to2", "700", "-o", path,
                   "--format", "json"]
    rc, out, err = stopped(args, signal.SIGINT, tmp_path)
    assert rc == 3, err
    report = json.loads(out)
    params = [p["param"] for p in report["points"]]
    assert report["stop"] == "stopped by SIGINT" and report["curves"] == [] and params[0] == 3.0
    assert err == (f"vibromap: stopped by SIGINT after {len(params)} points, before the first curve: the output above "
                   f"and {path} hold the continuation so far ({path}: a branch file, the branch so far) (stop: "
                   "'stopped by SIGINT'); continue has no --resume: run it again to go on\n")
    with h5py.File(path, "r") as f:
        assert f.attrs["title"] == "vibromap periodic-orbit branch"
        assert f.attrs["stop"] == "stopped by SIGINT"
        assert list(f["param"][()]) == params
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.h5"]


# The start orbit alone would take hours (FOREVER: an undamped chatter integrated for up to 10^8
# periods, as test_stop_in_flight.py's items).


def test_a_stop_while_the_start_orbit_is_solved_writes_nothing(tmp_path):
    scene = tmp_path / "forever.toml"
    scene.write_text(FOREVER)
    path = tmp_path / "branch.h5"
    rc, out, err = stopped(["continue", scene, "-p", "forcing.omega", "--from", "7.23", "--to", "8", "-o", path],
                           signal.SIGTERM, tmp_path)
    assert rc == 3, err
    assert out == ""
    assert err == ("vibromap: stopped by SIGTERM while solving the start orbit at forcing.omega = 7.23: no point found, "
                   "nothing written\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["forever.toml"]
