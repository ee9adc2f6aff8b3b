"""The faults a new user and a cluster operator met, each end with one clear line and the
documented exit code, on every rank, with no hang and no half-written file:

- a file-size limit (as a full disk) while the map is made: exit 4 on 1 and 2 ranks, no map left;
- a second run on a map that a first run is writing: exit 2, the first run unharmed;
- a grid whose map cannot fit on the disk, or whose cell count is absurd: exit 2 at once;
- an output folder that does not exist: exit 4 before any cell is computed.

Run by ctest (tests/campaigns/sweep_tests.cmake)."""
import os
import resource
import signal
import subprocess
import sys
import time

import h5py

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE, MPIEXEC, slow_scene  # noqa: E402

CHEAP = """
[forcing]
F0 = 0.0

[sweep]
E1 = {{ from = 2e4, to = 2.1e11, n = {n1}, scale = "log" }}
E2 = {{ from = 2e4, to = 2.1e11, n = {n2}, scale = "log" }}
progress_interval = 0.2
"""

SLOW = slow_scene(12, 8, progress=0.2)


def scene(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def run(cmd, limit_bytes=None, timeout=120):
    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))

    return subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=timeout,
                          preexec_fn=limit if limit_bytes else None)


def one_error_line(stderr):
    lines = [l for l in stderr.splitlines() if l.startswith("vibromap:")]
    assert len(lines) == 1, stderr
    return lines[0]


def test_a_full_disk_while_the_map_is_made_ends_every_rank_with_exit_4(tmp_path):
    """RLIMIT_FSIZE of 8 MB and a 10 MB map: the write fails with EFBIG as on a full disk.
    Before: a segfault (exit 139) in HDF5's clean-up on 1 rank, a hang on 2."""
    path = scene(tmp_path, CHEAP.format(n1=400, n2=400))
    for cmd in ([EXE, "sweep", str(path), "-o", str(tmp_path / "one.h5"), "-q"],
                [MPIEXEC, "-n", "2", EXE, "sweep", str(path), "-o", str(tmp_path / "two.h5"), "-q"]):
        for _ in range(3):
            proc = run(cmd, limit_bytes=8 << 20, timeout=60)
            assert proc.returncode == 4, proc.stderr
            line = one_error_line(proc.stderr)
            # Seen once in a CI run under load (2026-11-25): the limit also applies to Open MPI,
            # whose own failure then came back as the message (an Open MPI banner of dashes)
            # before the map's write failed. That is the library, not the map: try again.
            if not line.startswith("vibromap: error: ---"):
                break
        assert line.startswith("vibromap: error: ") and "File too large" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.toml"], "no map and no lock left behind"


def test_a_second_run_on_a_map_being_written_is_refused(tmp_path):
    path = scene(tmp_path, SLOW)
    out = tmp_path / "map.h5"
    first = subprocess.Popen([EXE, "sweep", str(path), "-o", str(out)], env=ENV, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    for line in first.stderr:  # wait until the first run computes
        if line.startswith("sweep: ") and int(line.split()[1].split("/")[0]) >= 2:
            break
    for flag in ("--resume", "--overwrite"):
        second = run([EXE, "sweep", str(path), "-o", str(out), "-q", flag], timeout=60)
        assert second.returncode == 2, second.stderr
        line = one_error_line(second.stderr)
        assert f"{out}: another vibromap run is writing it (pid {first.pid} on host " in line
    first.send_signal(signal.SIGTERM)
    first.stderr.read()
    assert first.wait(timeout=120) == 3
    with h5py.File(out, "r") as f:  # the first run's map is intact
        assert f["done"][()].sum() >= 2
    assert not (tmp_path / "map.h5.lock").exists()
    resumed = run([EXE, "sweep", str(path), "-o", str(out), "-q", "--resume"])
    assert resumed.returncode == 0, resumed.stderr  # the lock went with the first run


def test_grids_that_cannot_fit_are_refused_at_once(tmp_path):
    t0 = time.time()
    huge = run([EXE, "sweep", str(scene(tmp_path, CHEAP.format(n1=1000000, n2=1000000), "huge.toml")),
                "-o", str(tmp_path / "huge.h5"), "-q"], timeout=60)
    assert huge.returncode == 4, huge.stderr  # a resource (the disk) that cannot hold it: exit 4
    assert "cells needs" in one_error_line(huge.stderr) and "GB free" in huge.stderr
    three = CHEAP.format(n1=1000000, n2=1000000) + 'R1 = { from = 0.1, to = 2.0, n = 1000000 }\n'
    absurd = run([EXE, "sweep", str(scene(tmp_path, three, "absurd.toml")), "-o", str(tmp_path / "absurd.h5"), "-q"],
                 timeout=60)
    assert absurd.returncode == 2, absurd.stderr
    assert "the grid has 1e+18 cells" in one_error_line(absurd.stderr)
    assert time.time() - t0 < 30, "refused up front, not after allocating or computing"
    assert not (tmp_path / "huge.h5").exists() and not (tmp_path / "absurd.h5").exists()


def test_a_missing_output_folder_is_reported_before_computing(tmp_path):
    path = scene(tmp_path, SLOW)
    t0 = time.time()
    proc = run([MPIEXEC, "-n", "2", EXE, "sweep", str(path), "-o", str(tmp_path / "no_such_dir" / "m.h5"), "-q"])
    assert proc.returncode == 4, proc.stderr
    assert "directory" in one_error_line(proc.stderr) and "does not exist" in proc.stderr
    assert time.time() - t0 < 20
