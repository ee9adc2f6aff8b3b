"""Every command that writes a file writes it the one safe way (io/output_file.hpp).

An output that is a symbolic link, a character device node, a FIFO or a directory is refused
with exit 2 and one line, before any work: the link's target and the node are untouched and
nothing is left beside them. An existing regular file is replaced only with --overwrite, by a
new file renamed over it (so a hard link to the old file keeps the old content), and no
temporary file is left. Each command runs as one process (an MPI singleton), as a user runs it.
"""
import os
import stat
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from campaign_helpers import ENV, EXE  # noqa: E402

TINY_SWEEP = """
[system]
m2 = 310.0
omega2 = 3.606

[sweep]
E2 = { from = 1e6, to = 2e6, n = 2 }
"""

# Each writing command with OUT for its output; --overwrite given, so only the kind of OUT decides.
COMMANDS = {
    "run": ["run", "jobs/paper/table1.toml", "--overwrite", "-t", "OUT"],
    "sweep": ["sweep", "SWEEP", "-q", "--overwrite", "-o", "OUT"],
    "optimise": ["optimise", "jobs/paper/optimise_box.toml", "--overwrite", "-o", "OUT"],
    "continue": ["continue", "jobs/paper/table1.toml", "-p", "forcing.omega", "--from", "7.2", "--to", "7.25",
                 "--overwrite", "-o", "OUT"],
    "orbit-diagram": ["orbit-diagram", "jobs/paper/table1.toml", "-p", "omega", "--from", "7.2", "--to", "7.25",
                      "-n", "2", "--transient", "5", "--keep", "1", "-q", "--overwrite", "-o", "OUT"],
    "basins": ["basins", "jobs/paper/table1.toml", "--grid", "2x2", "-q", "--overwrite", "-o", "OUT"],
    "accuracy": ["accuracy", "jobs/paper/table1.toml", "-q", "--overwrite", "--csv", "OUT"],
}


def command(name, out, tmp_path):
    sweep = tmp_path / "tiny_sweep.toml"
    sweep.write_text(TINY_SWEEP)
    return [EXE] + [str(out) if a == "OUT" else str(sweep) if a == "SWEEP" else a for a in COMMANDS[name]]


def run(args, timeout=120):
    return subprocess.run(args, capture_output=True, text=True, env=ENV, timeout=timeout)


def one_error_line(stderr):
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("vibromap: error: "), stderr
    return lines[0]


def make_link(path, tmp_path):
    canary = tmp_path / "canary.txt"
    canary.write_text("the link's target\n")
    os.symlink(canary, path)
    return lambda: (path.is_symlink() and canary.read_text() == "the link's target\n")


def make_device(path, tmp_path):
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    os.mknod(path, 0o666 | stat.S_IFCHR, os.makedev(1, 3))  # the null device's numbers
    return lambda: stat.S_ISCHR(os.lstat(path).st_mode)


def make_fifo(path, tmp_path):
    os.mkfifo(path)
    return lambda: stat.S_ISFIFO(os.lstat(path).st_mode)


def make_directory(path, tmp_path):
    path.mkdir()
    return lambda: path.is_dir() and not any(path.iterdir())


KINDS = {"a symbolic link": make_link, "a character device": make_device, "a FIFO": make_fifo,
         "a directory": make_directory}


@pytest.mark.parametrize("kind", list(KINDS))
@pytest.mark.parametrize("name", list(COMMANDS))
def test_an_output_that_is_not_a_regular_file_is_refused_untouched(tmp_path, name, kind):
    out = tmp_path / "out.h5"
    intact = KINDS[kind](out, tmp_path)
    args = command(name, out, tmp_path)
    before = sorted(os.listdir(tmp_path))
    proc = run(args)
    assert proc.returncode == 2, proc.stderr
    line = one_error_line(proc.stderr)
    assert f"is {kind}" in line, line
    assert proc.stdout == ""
    assert intact(), f"{kind} was changed"
    assert sorted(os.listdir(tmp_path)) == before, "nothing is written beside it"


@pytest.mark.parametrize("name", ["run", "sweep", "accuracy", "basins"])
def test_overwrite_renames_a_new_file_over_the_old_one(tmp_path, name):
    out = tmp_path / "out.h5"
    out.write_text("the old file\n")
    twin = tmp_path / "twin.h5"
    os.link(out, twin)  # a hard link: an in-place write would change it too
    without = run([a for a in command(name, out, tmp_path) if a != "--overwrite"])
    assert without.returncode == 2 and "already exists" in one_error_line(without.stderr)
    assert out.read_text() == "the old file\n"
    proc = run(command(name, out, tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert twin.read_text() == "the old file\n", "the old file was written in place"
    assert os.stat(out).st_ino != os.stat(twin).st_ino
    assert os.stat(out).st_size > 0
    left = [p for p in os.listdir(tmp_path) if p.endswith(".tmp") or p.endswith(".lock")]
    assert left == [], left


@pytest.mark.parametrize("name", list(COMMANDS))
def test_empty_and_too_long_output_names_are_refused(tmp_path, name):
    empty = run(command(name, "", tmp_path))
    assert empty.returncode == 2 and "empty; name the file to write" in one_error_line(empty.stderr)
    long_name = tmp_path / ("x" * 300)
    long = run(command(name, long_name, tmp_path))
    assert long.returncode == 2, long.stderr
    assert "the file name is 300 bytes long; at most 240" in one_error_line(long.stderr)
    assert not any(p.startswith("x") for p in os.listdir(tmp_path))


def test_a_lock_file_that_is_a_link_is_refused(tmp_path):
    out = tmp_path / "out.h5"
    canary = tmp_path / "canary.txt"
    canary.write_text("keep me\n")
    os.symlink(canary, tmp_path / "out.h5.lock")
    proc = run(command("sweep", out, tmp_path))
    assert proc.returncode == 2, proc.stderr
    assert "out.h5.lock: is a symbolic link" in one_error_line(proc.stderr)
    assert canary.read_text() == "keep me\n" and not out.exists()


@pytest.mark.parametrize("side", ["_trajectory.h5", "_map.h5"])
@pytest.mark.parametrize("kind", ["link", "directory"])
def test_optimise_refuses_a_bad_side_file_before_making_any(tmp_path, side, kind):
    """optimise writes OUT, OUT.journal, OUT_map.h5 (the seeding sweep) and OUT_trajectory.h5:
    a link or a folder in place of one written last is refused before the others are made (the
    fuzzer found a journal and a seeding map left behind by a link at OUT_trajectory.h5)."""
    out = tmp_path / "o.h5"
    bad = tmp_path / ("o" + side)
    intact = make_link(bad, tmp_path) if kind == "link" else make_directory(bad, tmp_path)
    proc = run(command("optimise", out, tmp_path))
    assert proc.returncode == 2, proc.stderr
    line = one_error_line(proc.stderr)
    assert str(bad) in line and ("symbolic link" in line if kind == "link" else "directory" in line), line
    assert intact()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        ["tiny_sweep.toml", bad.name] + (["canary.txt"] if kind == "link" else [])), list(tmp_path.iterdir())
