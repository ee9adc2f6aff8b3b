"""Runs a notebook of docs/notebooks/ and checks every number it shows against the command line.

usage: check_notebook.py NOTEBOOK SOURCE_DIR [--images DIR]

The notebook is executed with nbclient in a kernel of this interpreter (the one vibromap._core
is built for; PYTHONPATH must reach the package, VIBROMAP_EXE names the built program), from
the notebook's folder as Jupyter would start it. Then:
  - the file itself must carry no outputs (it is committed stripped);
  - no cell may raise;
  - each cell that shows output must carry a tag with a check below (cell metadata "tags"); a
    check reads the lines the cell prints, each one or more "name = value" (optionally after
    "label: ", separated by ", "), and wants exactly the names it knows, each value as Python
    prints the number the command line gives for the same scene (repr of a float: bit for bit);
  - a cell that draws shows an image; a cell that runs the farm shows its progress bar, ended full.
--images DIR writes each cell's pictures to DIR/tour_<cell id>.png (the pictures of the docs).

Exit status: 0 when every cell ran and every number agrees; 1 otherwise (one line each);
77 when nbclient or ipykernel cannot be imported (the reason on stdout; ctest's skip code).
"""

from __future__ import annotations

import argparse
import base64
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Callable, Dict, List

TABLE2 = "jobs/paper/table2.toml"
PAIR = re.compile(r"^(\w+) *= *(\S+)$")
LABEL = re.compile(r"^([^=]+?): (.*)$")


class Reference:
    """The numbers of the built program (VIBROMAP_EXE) for the scenes the notebook solves."""

    def __init__(self, source_dir: Path, scratch: Path):
        self.top = source_dir
        self.scratch = scratch
        self.exe = os.environ.get("VIBROMAP_EXE", str(source_dir / "build" / "vibromap"))

    def run(self, *args: str, sets: tuple = ()) -> subprocess.CompletedProcess:
        """The program run with args and a --set for each of sets; RuntimeError unless it succeeds."""
        for s in sets:
            args = (*args, "--set", s)
        p = subprocess.run([self.exe, *args], cwd=self.top, capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError(f"{self.exe} {' '.join(args)}: exit {p.returncode}: {p.stderr.strip()}")
        return p

    def json(self, scene: str, *sets: str, flags: tuple = ()) -> dict:
        return json.loads(self.run("run", scene, "--format", "json", *flags, sets=sets).stdout)

    def trajectory(self, scene: str, *sets: str) -> Dict[str, object]:
        import h5py
        import numpy as np

        path = self.scratch / "trajectory.h5"
        self.run("run", scene, "--trajectory", str(path), "--overwrite", sets=sets)
        with h5py.File(path, "r") as f:
            return {"samples": int(f["t"].shape[0]), "T": float(f.attrs["T"]),
                    "Fc_max": float(np.max(f["Fc"][...]))}


def shown(text: str, errors: List[str], where: str) -> Dict[str, str]:
    """The "name = value" pairs of a cell's printed text, by "label.name" (or name)."""
    out: Dict[str, str] = {}
    for line in text.splitlines():
        if not line.strip():
            continue
        label, rest = "", line
        m = LABEL.match(line)
        if m and "=" not in m.group(1):
            label, rest = m.group(1).strip() + ".", m.group(2)
        for pair in rest.split(", "):
            p = PAIR.match(pair.strip())
            if not p:
                errors.append(f"{where}: line '{line}' is not 'name = value, ...'")
                break
            out[label + p.group(1)] = p.group(2)
    return out


def as_printed(value: object) -> str:
    """A value as the notebook prints it: repr for a float (round trip, so bit for bit)."""
    if isinstance(value, float):
        return repr(value)
    return str(value)


def compare(where: str, got: Dict[str, str], want: Dict[str, object], errors: List[str]) -> None:
    for name in sorted(set(want) - set(got)):
        errors.append(f"{where}: does not show {name} (the command line's: {as_printed(want[name])})")
    for name in sorted(set(got) - set(want)):
        errors.append(f"{where}: shows {name} = {got[name]}, which no reference covers")
    for name in sorted(set(got) & set(want)):
        if got[name] != as_printed(want[name]):
            errors.append(f"{where}: {name} = {got[name]}, the command line's is {as_printed(want[name])}")


def pick(d: dict, *names: str) -> Dict[str, object]:
    return {n: d[n] for n in names}


def check_point(ref: Reference) -> Dict[str, object]:
    return pick(ref.json(TABLE2), "regime", "T_con", "k_con", "z_ratio", "soft")


def check_changed(ref: Reference) -> Dict[str, object]:
    return pick(ref.json(TABLE2, "contact.E2=1e8"), "regime", "k_con", "F_max", "soft")


def check_trajectory(ref: Reference) -> Dict[str, object]:
    return ref.trajectory(TABLE2, "analysis.trajectory_periods=2")


def check_census(ref: Reference) -> Dict[str, object]:
    c = ref.json(TABLE2, "census.initial_conditions=32", flags=("--census",))
    want: Dict[str, object] = {"soft_fraction": c["soft_fraction"]}
    for a in c["attractors"]:
        for name in ("fraction", "k_con", "soft"):
            key = f"{a['regime']}.{name}"
            if key in want:
                raise RuntimeError(f"the census lists two attractors {a['regime']}: name them apart in the cell")
            want[key] = a[name]
    return want


MAP_AXES = ('sweep.E2={from = 1e5, to = 1e9, n = 8, scale = "log"}', "sweep.omega={from = 6, to = 8, n = 8}")


def check_map(ref: Reference) -> Dict[str, object]:
    """The notebook's map made on 2 ranks; this reference on 1 (the cells are independent: the
    rank count changes no cell, so agreeing also checks that)."""
    import h5py
    import numpy as np

    path = ref.scratch / "map.h5"
    ref.run("sweep", TABLE2, "-o", str(path), "--quiet", sets=MAP_AXES)
    with h5py.File(path, "r") as f:
        k_con, soft = f["k_con"][...], f["soft"][...]
    return {"cells": int(k_con.size), "soft": int(np.count_nonzero(soft == 1)), "k_con_max": float(np.nanmax(k_con))}


def check_branch(ref: Reference) -> Dict[str, object]:
    """The first branch's points and folds (the doubled branches are under "branches")."""
    d = json.loads(ref.run("continue", TABLE2, "--param", "omega", "--from", "7.23", "--to", "9",
                           "--format", "json", "-o", str(ref.scratch / "branch.h5")).stdout)
    folds = [b["param"] for b in d["bifurcations"] if b["type"] == "fold"]
    if not folds:
        raise RuntimeError("the branch has no fold: the cell has nothing to show")
    want: Dict[str, object] = {"points": len(d["points"])}
    for i, p in enumerate(folds):
        want[f"fold {i}.omega"] = p
    return want


# The cells that run the farm, whose progress bar must end full.
SHOWS_PROGRESS = ("map",)

# A tag's check: the names and values its cell must show, and whether it draws.
CHECKS: Dict[str, tuple[Callable[[Reference], Dict[str, object]], bool]] = {
    "point": (check_point, False),
    "changed": (check_changed, False),
    "trajectory": (check_trajectory, True),
    "census": (check_census, False),
    "map": (check_map, True),
    "branch": (check_branch, True),
}


PROGRESS = re.compile(r'^<progress value="(\d+)" max="(\d+)"')


def cell_text(cell) -> tuple[str, str, List[bytes], List[tuple[int, int]]]:
    """The cell's printed text (stdout and results), its stderr, its PNG pictures and its
    progress bars as (done, total) where they ended (vibromap.sweep's, updated in place)."""
    text, err, images, bars = [], [], [], []
    for o in cell.get("outputs", []):
        if o.output_type == "stream":
            (text if o.name == "stdout" else err).append(o.text)
        elif o.output_type in ("execute_result", "display_data"):
            bar = PROGRESS.match(o.data.get("text/html", ""))
            if bar:
                bars.append((int(bar.group(1)), int(bar.group(2))))
            elif "image/png" in o.data:
                images.append(base64.b64decode(o.data["image/png"]))
            elif "text/plain" in o.data:
                text.append(o.data["text/plain"] + "\n")
    return "".join(text), "".join(err), images, bars


def stored_outputs(nb, name: str, errors: List[str]) -> None:
    for cell in nb.cells:
        if cell.cell_type == "code" and (cell.get("outputs") or cell.get("execution_count") is not None):
            errors.append(f"{name}: cell '{cell.get('id')}' is committed with outputs (strip them: "
                          "jupyter nbconvert --clear-output --inplace, or clear them in Jupyter)")


def kernel_of_this_python(scratch: Path) -> str:
    """A kernel spec that starts this interpreter (Debian's python3 spec may name another)."""
    spec = scratch / "kernels" / "vibromap-check"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "vibromap check", "language": "python"}))
    os.environ["JUPYTER_PATH"] = str(scratch)
    return "vibromap-check"


def execute(nb, folder: Path, scratch: Path):
    from nbclient import NotebookClient

    # Pictures inline, as Jupyter shows them, even where MPLBACKEND names a file backend; the
    # kernel starts in the notebook's folder, so a relative PYTHONPATH is made absolute; and the
    # debugger's note on frozen modules (Python 3.11) is kept out of the log.
    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    paths = os.environ.get("PYTHONPATH", "").split(os.pathsep)
    os.environ["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in paths if p)
    os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"
    client = NotebookClient(nb, timeout=300, kernel_name=kernel_of_this_python(scratch),
                            allow_errors=True, resources={"metadata": {"path": str(folder)}})
    return client.execute()


def check_cells(nb, name: str, ref: Reference, images_dir: Path | None, errors: List[str]) -> None:
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        where = f"{name}: cell '{cell.get('id')}'"
        failed = [o for o in cell.get("outputs", []) if o.output_type == "error"]
        if failed:
            errors.append(f"{where} failed: {failed[0].ename}: {failed[0].evalue}")
            continue
        text, err, images, bars = cell_text(cell)
        if err:
            errors.append(f"{where} writes to stderr: {err.strip().splitlines()[-1]}")
        tags = [t for t in cell.metadata.get("tags", []) if t in CHECKS]
        if not tags:
            if text or images:
                errors.append(f"{where} shows output that no check covers (tag it with one of {', '.join(CHECKS)})")
            continue
        want, draws = CHECKS[tags[0]]
        try:
            compare(where, shown(text, errors, where), want(ref), errors)
        except RuntimeError as e:
            errors.append(f"{where}: reference: {e}")
        if draws and not images:
            errors.append(f"{where} draws no picture")
        if tags[0] in SHOWS_PROGRESS and (not bars or bars[-1][0] != bars[-1][1]):
            errors.append(f"{where} shows no progress bar that ends full (shown: {bars})")
        if images_dir is not None:
            for i, png in enumerate(images):
                suffix = f"_{i}" if i else ""
                (images_dir / f"tour_{cell.get('id')}{suffix}.png").write_bytes(png)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook", type=Path)
    parser.add_argument("source_dir", type=Path)
    parser.add_argument("--images", type=Path, help="write the pictures to DIR/tour_<cell id>.png")
    args = parser.parse_args()
    try:
        import ipykernel  # noqa: F401  (the kernel nbclient starts)
        import nbclient  # noqa: F401
        import nbformat
    except ImportError as e:
        print(f"skipped: {e.name} cannot be imported by {sys.executable} (Debian: python3-nbclient python3-ipykernel, in .ci/setup.sh)")
        return 77

    name = args.notebook.name
    nb = nbformat.read(args.notebook, as_version=4)
    errors: List[str] = []
    stored_outputs(nb, name, errors)
    with tempfile.TemporaryDirectory(prefix="vibromap-notebook-") as tmp:
        scratch = Path(tmp)
        if args.images is not None:
            args.images.mkdir(parents=True, exist_ok=True)
        nb = execute(nb, args.notebook.resolve().parent, scratch)
        check_cells(nb, name, Reference(args.source_dir.resolve(), scratch), args.images, errors)
    for e in errors:
        print(e)
    if errors:
        print(f"{name}: {len(errors)} disagreement(s)")
        return 1
    print(f"{name}: every cell ran, every number agrees with the command line")
    return 0


if __name__ == "__main__":
    sys.exit(main())
