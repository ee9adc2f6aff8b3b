"""The scripts of vibromap-post, one command for every picture and summary of vibromap's files:

    vibromap-post SCRIPT [ARGS...]     SCRIPT's main with ARGS (SCRIPT --help: its options)
    vibromap-post --help               this usage and the scripts

postprocess/vibromap-post in a checkout, the same file installed as PREFIX/bin/vibromap-post,
finds a Python that imports numpy, h5py and matplotlib and runs `python -m vibromap SCRIPT
ARGS`, which is this module's main; pip's console script vibromap-post is it too.

Each script is a module of the package whose main(argv=None) returns the exit status: 0 done, 2
a bad argument or an unreadable input (one line on stderr). Run from here it reads its files in
a forked child (vibromap._guard), so that a file that crashes the HDF5 library is one line and
exit status 2 too. A missing numpy, h5py or matplotlib is one line and exit status 3.

Standard library only until a script is imported, so that a missing module is reported as such.
"""

from __future__ import annotations

import importlib
import sys

PROG = "vibromap-post"
EXIT_USAGE, EXIT_MISSING_MODULE = 2, 3

# The scripts: name -> the module whose main(argv) it runs.
SCRIPTS = {
    "summarize_map": "vibromap._summarize_map",
    "plot_basins": "vibromap.plot._basins",
    "plot_branch": "vibromap.plot._branch",
    "plot_census_map": "vibromap.plot._census_map",
    "plot_kcon_map": "vibromap.plot._kcon_map",
    "plot_optimise": "vibromap.plot._optimise",
    "plot_orbit_diagram": "vibromap.plot._orbit_diagram",
    "plot_regime_map": "vibromap.plot._regime_map",
    "plot_restitution": "vibromap.plot._restitution",
    "plot_soft_map": "vibromap.plot._soft_map",
    "plot_trajectory": "vibromap.plot._trajectory",
    "plot_work_precision": "vibromap.plot._work_precision",
}


def usage() -> str:
    names = "".join(f"  {name}\n" for name in sorted(SCRIPTS))
    return (f"usage: {PROG} SCRIPT [ARGS...] | {PROG} --print\n"
            f"scripts ({PROG} SCRIPT --help for each):\n{names}"
            f"--print: the Python interpreter the launcher postprocess/vibromap-post runs\n")


def missing_module(prog: str, exc: ImportError) -> int:
    """One line naming the missing module and the launcher to use; exit status 3."""
    print(f"{prog}: error: {exc} (in {sys.executable}); run it as {PROG} {prog} ..., which finds a Python "
          "with numpy, h5py and matplotlib", file=sys.stderr)
    return EXIT_MISSING_MODULE


def load(prog: str):
    """The script's module, with matplotlib drawing to files only (no display on a cluster node)."""
    try:
        import matplotlib

        matplotlib.use("Agg")
    except ImportError:
        pass  # summarize_map needs no matplotlib; a picture's import says what is missing
    return importlib.import_module(SCRIPTS[prog])


def main(argv: list[str] | None = None) -> int:
    """Runs `SCRIPT ARGS...` (argv, else sys.argv[1:]); the script's exit status."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv:
        print(usage(), end="", file=sys.stderr)
        return EXIT_USAGE
    if argv[0] in ("-h", "--help"):
        print(usage(), end="")
        return 0
    prog = argv[0][:-3] if argv[0].endswith(".py") else argv[0]
    if prog not in SCRIPTS:
        print(f"{PROG}: error: no postprocess script '{prog}' (see {PROG} --help)", file=sys.stderr)
        return EXIT_USAGE
    try:
        script = load(prog)
    except ImportError as exc:
        return missing_module(prog, exc)
    sys.argv = [prog, *argv[1:]]  # the script's guard reads its arguments from there
    return script.main()
