"""vibromap_guard: a script run as a program reads its files in a forked child, so that a crash
in the HDF5 C library (a signal no try/except catches) ends in one line naming the HDF5 file and
exit 2, while everything else (stdout, stderr, the exit status) passes through; main(argv) with an
explicit list runs in the calling process. The crash is made here by the child killing itself
with the signal the HDF5 library dies of on a damaged map (SIGSEGV, or SIGABRT from glibc's
"free(): invalid size", which it prints first: held back, so the line stays one line)."""
import os
import sys

import h5py
import pytest

import conftest
from conftest import run
from vibromap._guard import guarded_main

PROGRAM = """
import os, signal, sys
sys.path.insert(0, {postprocess!r})
from vibromap._guard import guarded_main

@guarded_main("prog")
def main(argv=None):
    what = sys.argv[2]
    if what == "crash":
        sys.stderr.write("free(): invalid size\\n")
        sys.stderr.flush()
        os.kill(os.getpid(), getattr(signal, sys.argv[3]))
    if what == "raise":
        raise RuntimeError("a bug of the script's own")
    print("drew it")
    print("prog: note: a note", file=sys.stderr)
    return int(sys.argv[3])

sys.exit(main())
"""


@pytest.fixture()
def program(tmp_path):
    path = tmp_path / "program.py"
    path.write_text(PROGRAM.format(postprocess=conftest.POSTPROCESS_DIR))
    data = tmp_path / "map.h5"
    with h5py.File(data, "w") as f:
        f.attrs["title"] = "vibromap regime map"
    return path, data


@pytest.mark.parametrize("sig", ["SIGSEGV", "SIGABRT", "SIGBUS"])
def test_a_crash_reading_a_file_is_one_line_naming_it_and_exit_2(program, sig):
    path, data = program
    proc = run([sys.executable, str(path), str(data), "crash", sig])
    assert (proc.returncode, proc.stdout) == (2, "")
    assert proc.stderr == (f"prog: error: {data}: damaged: reading it crashed the HDF5 library ({sig}); "
                           "make it again with vibromap --overwrite\n")


@pytest.mark.parametrize("code", [0, 1, 2])
def test_output_and_exit_status_pass_through(program, code):
    path, data = program
    proc = run([sys.executable, str(path), str(data), "draw", str(code)])
    assert (proc.returncode, proc.stdout, proc.stderr) == (code, "drew it\n", "prog: note: a note\n")


def test_a_traceback_of_the_scripts_own_is_not_taken_for_damage(program):
    path, data = program
    proc = run([sys.executable, str(path), str(data), "raise", "0"])
    assert proc.returncode == 1
    assert proc.stderr.splitlines()[-1] == "RuntimeError: a bug of the script's own"


def test_an_explicit_argv_runs_in_this_process():
    pid = []

    @guarded_main("prog")
    def main(argv=None):
        pid.append(os.getpid())
        return 3

    assert main(["x"]) == 3
    assert pid == [os.getpid()]  # a forked child could not have appended here
