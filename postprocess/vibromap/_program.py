"""Running the vibromap program for the studies of _studies.py: finding it, its launcher
(mpirun for several ranks), the scene as its arguments, its progress, its stop on Ctrl-C
(SIGUSR1, then the final checkpoint) and its answer or its one-line error.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Callable, Dict, List, Optional, Tuple

from ._native import _core
from ._scene import Scene, Value

_ERROR_PREFIX = "vibromap: error: "
_STOPPED_PREFIX = "vibromap: stopped by "  # the line of a program its stop signal ended
_EXIT_BAD_INPUT, _EXIT_STOPPED, _EXIT_IO = 2, 3, 4
# How long a stopped program may take for its final checkpoint before KeyboardInterrupt is
# raised without it (it goes on in its own session and still writes it).
_STOP_WAIT_S = 30.0
_CENSUS_K = 32  # initial states of a census map whose scene has no [census] (the guide's default)
# The farm's progress line (parallel/progress.cpp): "sweep: 12/60 cells (20.0%), 11.4 cells/s, ...".
_PROGRESS = re.compile(r"^(\w[\w -]*): (\d+)/(\d+) (\w+) \(")


# ---- the program ---------------------------------------------------------------------------

def _program() -> str:
    """The vibromap executable: VIBROMAP_EXE, else next to the package, else on PATH."""
    named = os.environ.get("VIBROMAP_EXE")
    if named:
        return named
    here = Path(__file__).resolve().parent
    beside = (here.parent.parent / "vibromap",  # build/python/vibromap -> build/vibromap
              here.parents[3] / "bin" / "vibromap")  # PREFIX/lib/python3.X/dist-packages/vibromap -> PREFIX/bin
    for candidate in beside:
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return str(candidate)
    found = shutil.which("vibromap")
    if found:
        return found
    raise FileNotFoundError(f"the vibromap program is neither beside the package ({beside[0]}, {beside[1]}) nor on "
                            "PATH: build it (cmake --build build) or name it with VIBROMAP_EXE")


def _launcher(ranks: int) -> List[str]:
    """``mpirun -n N`` (with Open MPI's flags for root and for more ranks than cores), or nothing
    for one rank, which the program runs alone."""
    if not isinstance(ranks, int) or isinstance(ranks, bool) or ranks < 1:
        raise ValueError(f"ranks = {ranks!r}: must be an integer >= 1")
    if ranks == 1:
        return []
    mpirun = shutil.which("mpirun") or shutil.which("mpiexec")
    if mpirun is None:
        raise FileNotFoundError(f"ranks = {ranks}: no mpirun or mpiexec on PATH (ranks=1 runs without MPI)")
    args = [mpirun, "-n", str(ranks)]
    version = subprocess.run([mpirun, "--version"], capture_output=True, text=True).stdout
    if "Open MPI" in version or "OpenRTE" in version:
        if os.geteuid() == 0:
            args.append("--allow-run-as-root")
        if ranks > (os.cpu_count() or 1):
            args.append("--oversubscribe")
    return args


class _SceneArgs:
    """The scene as the program's arguments: its file and --set overrides, or a temporary copy
    of its text (removed by close()), with what messages call that copy."""

    def __init__(self, scene: Scene, keys: Dict[str, Value]) -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"takes a vibromap.Scene, not {type(scene).__name__} (Scene.from_toml(path))")
        self.scene = scene.with_(**keys) if keys else scene
        self.folder: Optional[str] = None
        self.copy: Optional[str] = None
        origin = self.scene._origin
        if origin is not None and self._reads_back(origin):
            self.args = [origin[0]] + [a for o in origin[1] for a in ("--set", o)]
            return
        self.folder = tempfile.mkdtemp(prefix="vibromap-scene-")
        name = os.path.basename(self.scene.path) if self.scene.path.endswith(".toml") else "scene.toml"
        self.copy = os.path.join(self.folder, name)
        with open(self.copy, "w", encoding="utf-8") as f:
            f.write(self.scene.to_toml())
        self.args = [self.copy]

    def _reads_back(self, origin: Tuple[str, Tuple[str, ...]]) -> bool:
        """Whether the file with its overrides still gives this scene (it may have changed)."""
        try:
            return _core.Scene.load(origin[0], list(origin[1])).text == self.scene.to_toml()
        except (ValueError, OSError):
            return False

    def message(self, line: str) -> str:
        return line.replace(self.copy, self.scene.path) if self.copy else line

    def close(self) -> None:
        if self.folder:
            shutil.rmtree(self.folder, ignore_errors=True)


# ---- progress ------------------------------------------------------------------------------

class _Progress:
    """Shows the program's progress: in a Jupyter notebook a bar updated in place (the farm's
    latest line parsed: done of total, with the line beside it; IPython.display); elsewhere the
    program's own lines on stderr as they come. Other lines go to stderr in both."""

    def __init__(self, shown: bool) -> None:
        self.shown = shown
        self.handle = None
        if shown and _in_notebook():
            from IPython.display import display

            self.handle = display(_bar(0, 1, "starting"), display_id=True)

    @property
    def notebook(self) -> bool:
        return self.handle is not None

    def line(self, text: str) -> None:
        match = _PROGRESS.match(text)
        if match:
            if not self.shown:
                return
            if self.handle is not None:
                self.handle.update(_bar(int(match.group(2)), int(match.group(3)), text))
                return
        sys.stderr.write(text + "\n")
        sys.stderr.flush()


def _bar(done: int, total: int, text: str):
    """A progress bar for IPython.display: HTML <progress> and the line (its text form the line)."""
    import html

    from IPython.display import HTML

    class _Bar(HTML):
        def __repr__(self) -> str:
            return text

    return _Bar(f'<progress value="{done}" max="{max(total, 1)}" style="width:30em"></progress> '
                f"<code>{html.escape(text)}</code>")


def _in_notebook() -> bool:
    try:
        from IPython import get_ipython
    except ImportError:
        return False
    shell = get_ipython()
    return shell is not None and hasattr(shell, "kernel")


# ---- running ---------------------------------------------------------------------------------

class _Run:
    """The program's answer: its exit code, stdout, and stderr's lines."""

    def __init__(self, code: int, out: str, err: List[str]) -> None:
        self.code, self.out, self.err = code, out, err


def _reader(stream, sink: Callable[[str], None]) -> threading.Thread:
    def pump() -> None:
        for line in stream:
            sink(line.rstrip("\n"))

    t = threading.Thread(target=pump, daemon=True)
    t.start()
    return t


# Programs stopped by Ctrl-C that were still ending (mpirun tearing down its ranks) when
# KeyboardInterrupt was raised; the next run waits for them, as their lock files go with them.
_ENDING: List[subprocess.Popen] = []


def _execute(args: List[str], ranks: int, progress: Optional[_Progress] = None) -> _Run:
    """Runs ``[mpirun -n N] vibromap ARGS``; Ctrl-C stops it (SIGUSR1: a final checkpoint) and
    raises KeyboardInterrupt once it says it stopped."""
    while _ENDING:
        _ENDING.pop().wait()
    command = _launcher(ranks) + [_program()] + args
    proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    out: List[str] = []
    err: List[str] = []
    stopped = threading.Event()

    def on_err(line: str) -> None:
        err.append(line)
        if line.startswith(_STOPPED_PREFIX):
            stopped.set()
        if progress is not None:
            progress.line(line)

    threads = [_reader(proc.stdout, out.append), _reader(proc.stderr, on_err)]
    try:
        while proc.poll() is None:
            time.sleep(0.02)
    except KeyboardInterrupt:
        _stop(proc, stopped)
        raise
    for t in threads:
        t.join()
    return _Run(proc.returncode, "\n".join(out), err)


def _stop(proc: subprocess.Popen, stopped: threading.Event) -> None:
    """Stops the program as its stop signal does and waits until it has ended or says it stopped
    (its line comes after the final checkpoint: the files are whole then)."""
    try:
        proc.send_signal(signal.SIGUSR1)
    except ProcessLookupError:
        return
    deadline = time.monotonic() + _STOP_WAIT_S
    while proc.poll() is None and not stopped.is_set() and time.monotonic() < deadline:
        time.sleep(0.01)
    if proc.poll() is None:
        _ENDING.append(proc)


def _answer(run: _Run, scene: _SceneArgs, stopped_ok: bool = False) -> str:
    """stdout of a run that ended well; raises SceneError (exit 2), OSError (4), KeyboardInterrupt
    (3, stopped by another), RuntimeError (anything else) with the program's one line."""
    if run.code == 0 or (stopped_ok and run.code == _EXIT_STOPPED):
        return run.out
    errors = [line[len(_ERROR_PREFIX):] for line in run.err if line.startswith(_ERROR_PREFIX)]
    line = scene.message(errors[0] if errors else (run.err[-1] if run.err else f"exit code {run.code}"))
    if run.code == _EXIT_BAD_INPUT:
        raise _core.SceneError(line)
    if run.code == _EXIT_STOPPED:
        raise KeyboardInterrupt(line)
    if run.code == _EXIT_IO:
        raise OSError(line)
    raise RuntimeError(f"vibromap exited with code {run.code}: {line}")
