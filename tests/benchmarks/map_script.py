"""What the map benchmark scripts (profile_map.py, label_robustness.py) share: their common
options, running the tool, and the map's regime names."""
import argparse
import subprocess
import sys

import numpy as np


def parser(doc: str, name: str) -> argparse.ArgumentParser:
    """The options every map script takes: --exe, --ranks, --scene, --set."""
    p = argparse.ArgumentParser(prog=name, description=doc.splitlines()[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=doc)
    p.add_argument("--exe", default="build/vibromap")
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--scene", default="jobs/demo/e1_e2.toml")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    return p


def mpi_prefix(ranks: int) -> list:
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] if ranks > 1 else []


def run(name: str, args, **kw) -> subprocess.CompletedProcess:
    """Runs args; a failure ends the script with the command, its exit status and its stderr's end."""
    p = subprocess.run(args, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        sys.exit(f"{name}: {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr.strip()[-500:]}")
    return p


def regime_names(f) -> dict:
    """The map's regime codes to their names (its flag_values and flag_meanings), e.g. 0: 'periodic'."""
    meanings = f["regime"].attrs["flag_meanings"]
    meanings = meanings.decode() if isinstance(meanings, bytes) else str(meanings)
    return dict(zip(np.atleast_1d(f["regime"].attrs["flag_values"]).tolist(), meanings.split()))
