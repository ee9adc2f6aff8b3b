"""A script run as a program reads its files in a child process, so that a damaged HDF5 file
that crashes the HDF5 C library (a signal in C code, which no try/except can catch) ends in one
line and exit status 2, as vibromap's own refusals do, instead of a signal death of the
interpreter.

    @guarded_main(PROG)
    def main(argv=None) -> int: ...

main(None) (the program: sys.argv) runs the body in a forked child and waits for it. The child's
stdout passes through; its stderr is held back and printed when it ends by itself. When it dies
of SIGSEGV, SIGBUS, SIGABRT, SIGFPE or SIGILL, the one line names the HDF5 files among the
arguments: "PROG: error: map.h5: damaged: reading it crashed the HDF5 library (SIGSEGV); make it
again with vibromap --overwrite". main(argv) with an explicit list runs in the calling process
(tests, other Python code). Set VIBROMAP_NO_GUARD=1 to run the program in one process (a debugger).
"""

from __future__ import annotations

import functools
import os
import signal
import sys
import traceback

CRASHES = (signal.SIGSEGV, signal.SIGBUS, signal.SIGABRT, signal.SIGFPE, signal.SIGILL)


def _exit_code(code) -> int:
    if code is None:
        return 0
    return code if isinstance(code, int) else 1


def _child(work, write_end: int) -> None:
    """Runs work() with stderr on the pipe and leaves the process with its status."""
    os.dup2(write_end, 2)
    os.close(write_end)
    code = 1
    try:
        code = _exit_code(work())
    except SystemExit as exc:
        code = _exit_code(exc.code)
    except KeyboardInterrupt:
        code = 130
    except BaseException:  # noqa: BLE001 - the child's own traceback, as the program would print it
        traceback.print_exc()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)


def _hdf5_arguments(argv: list[str]) -> str:
    """The arguments that are HDF5 files (by their signature), for the crash's line."""
    import h5py

    files = [a for a in argv if os.path.isfile(a) and h5py.is_hdf5(a)]
    return ", ".join(files) if files else "an input file"


def crash_line(files: str, sig: signal.Signals) -> str:
    """What a read that crashed the HDF5 library is reported as (after "PROG: error: ")."""
    return f"{files}: damaged: reading it crashed the HDF5 library ({sig.name}); make it again with vibromap --overwrite"


def check_in_child(check, path: str) -> tuple[bool, str]:
    """check(path) -> str in a forked child: (True, its answer), or (False, the one-line message of
    the exception it raised, or crash_line when it died of a signal). In this process where
    there is no fork."""
    if not hasattr(os, "fork") or os.environ.get("VIBROMAP_NO_GUARD"):
        try:
            return True, check(path)
        except Exception as exc:  # noqa: BLE001 - the caller raises it as one line
            return False, str(exc)
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read_end)
        try:
            answer, code = check(path).encode(), 0
        except BaseException as exc:  # noqa: BLE001 - reported to the parent as its line
            answer, code = (str(exc) or type(exc).__name__).encode("utf-8", "replace"), 1
        os.write(write_end, answer)
        os._exit(code)
    os.close(write_end)
    held, status = _wait(pid, read_end)
    answer = held.decode("utf-8", "replace")
    if os.WIFSIGNALED(status):
        return False, crash_line(path, signal.Signals(os.WTERMSIG(status)))
    return os.WEXITSTATUS(status) == 0, answer


def _wait(pid: int, read_end: int):
    """What the child `pid` wrote to the pipe `read_end` until it ended, and its wait status;
    Ctrl-C kills the child (it may be stuck in the HDF5 library) and goes on as KeyboardInterrupt."""
    try:
        with os.fdopen(read_end, "rb") as pipe:
            held = pipe.read()
        _, status = os.waitpid(pid, 0)
    except KeyboardInterrupt:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        raise
    return held, status


def run_guarded(prog: str, work) -> int:
    """work() in a forked child (the module's docstring); its exit status."""
    sys.stdout.flush()
    sys.stderr.flush()
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read_end)
        _child(work, write_end)
    os.close(write_end)
    held, status = _wait(pid, read_end)
    if os.WIFSIGNALED(status):
        sig = signal.Signals(os.WTERMSIG(status))
        if sig in CRASHES:
            print(f"{prog}: error: {crash_line(_hdf5_arguments(sys.argv[1:]), sig)}", file=sys.stderr)
            return 2
        print(f"{prog}: error: stopped by {sig.name}", file=sys.stderr)
        return 128 + sig.value
    sys.stderr.buffer.write(held)
    sys.stderr.flush()
    return os.WEXITSTATUS(status)


def guarded_main(prog: str):
    """Decorates a script's main(argv=None): see the module's docstring."""

    def wrap(main):
        @functools.wraps(main)
        def guarded(argv=None):
            if argv is not None or os.environ.get("VIBROMAP_NO_GUARD") or not hasattr(os, "fork"):
                return main(argv)
            return run_guarded(prog, lambda: main(None))

        return guarded

    return wrap
