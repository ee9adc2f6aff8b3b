"""The compiled core, vibromap._core, when it is built for this interpreter; else a stand-in.

The solver (Scene, run, census, trajectory) needs the core; vibromap.files, vibromap.plot and
the scripts of vibromap-post are pure Python and work without it (PYTHONPATH=postprocess in a
checkout that was never built). Without the core, SceneError is a plain ValueError subclass and
every use of the core raises ImportError saying why it is missing and how to build it.
"""

from __future__ import annotations

import importlib


class _MissingCore:
    """Stands for vibromap._core when it cannot be imported: any use raises ImportError."""

    def __init__(self, reason: ImportError) -> None:
        self._reason = reason

    def __getattr__(self, name: str):
        raise ImportError(f"vibromap._core, the compiled solver, cannot be imported ({self._reason}): build it "
                          "(cmake --build build, then PYTHONPATH=build/python; docs/python.md); vibromap.files, "
                          "vibromap.plot and vibromap-post work without it") from self._reason


try:
    _core = importlib.import_module(f"{__package__}._core")

    SceneError = _core.SceneError
except ImportError as exc:
    _core = _MissingCore(exc)

    class SceneError(ValueError):
        """A bad key or value (the command line's one-line message); the solver raises it."""
