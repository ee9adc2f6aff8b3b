"""Where a map's time goes, and how far each part is from its floor (docs/benchmarks.md). From
the checkout's root, with a built tree:

    /usr/bin/python3 tests/benchmarks/profile_map.py [--exe build/vibromap] [--ranks 2]
        [--scene jobs/demo/e1_e2.toml] [--set KEY=VALUE ...] [--keep MAP.h5]

Makes the scene's map (`sweep.refine = 0`: the coarse level) on RANKS ranks with every cell's
solve stored by phase (the map quantities t_* and rhs_*: seconds and right-hand side
evaluations of the transients before shooting, shooting, brute force, brute force's Floquet
multipliers, classification) and prints:

  - time by phase over the whole map, core-seconds: setup (a cell's wall_s less its phases),
    each phase, and the farm and output (ranks x the sweep's wall time less the cells' wall_s;
    the checkpoints' writing apart);
  - time by cell class: no-contact, periodic, chatter, non-periodic (chaotic and
    quasi-periodic included), unresolved, other (permanent contact, failed): cells, seconds,
    milliseconds a cell, evaluations and periods a cell;
  - each phase's floor: its evaluations times the nanoseconds one evaluation costs in the
    leanest stepper (rk4 at 2^11 steps a period on Table 2, measured here: its wall time over
    its evaluations), and for the output the bytes written over the disk's rate (a 256 MB
    write and fsync here); and each phase's ratio to its floor.

The map is made in a temporary folder (or kept at --keep)."""
import json
import os
import shutil
import sys
import tempfile
import time

import h5py
import numpy as np

from map_script import mpi_prefix, parser as map_parser, regime_names, run as run_named

PHASES = ("transient", "newton", "integrate", "floquet", "classify")
PHASE_NAMES = {"transient": "transients before shooting", "newton": "shooting (Newton, checks, cycle)",
               "integrate": "brute force (following)", "floquet": "Floquet of brute force's orbit",
               "classify": "classification and impacts"}
# Regime codes to the classes of the profile (the map's regime flag_meanings name them).
CLASSES = {"no-contact": "no-contact", "periodic": "periodic", "chatter": "chatter", "non-periodic": "non-periodic",
           "quasi-periodic": "non-periodic", "chaotic": "non-periodic", "unresolved": "unresolved"}


def run(args, **kw):
    return run_named("profile_map", args, **kw)


def ns_per_evaluation(exe: str) -> float:
    """rk4 at 2^11 steps a period on Table 2: wall time over evaluations, the best of 3."""
    best = float("inf")
    for _ in range(3):
        d = json.loads(run([exe, "run", "jobs/paper/table2.toml", "--set", "solver.method=rk4",
                            "--set", "solver.rk4_steps=2048", "--format", "json"]).stdout)
        best = min(best, d["wall_s"] / d["rhs_evals"] * 1e9)
    return best


def disk_rate(folder: str) -> float:
    """Bytes per second of a 256 MB write with fsync in folder."""
    path = os.path.join(folder, "rate.bin")
    block = os.urandom(1 << 20)
    t = time.perf_counter()
    with open(path, "wb") as f:
        for _ in range(256):
            f.write(block)
        f.flush()
        os.fsync(f.fileno())
    rate = 256 * (1 << 20) / (time.perf_counter() - t)
    os.remove(path)
    return rate


def classes_of(f) -> np.ndarray:
    regime = f["regime"][...]
    table = {v: CLASSES.get(m.replace("_", "-"), "other") for v, m in regime_names(f).items()}
    return np.vectorize(lambda c: table.get(int(c), "other"), otypes=[object])(regime)


def main() -> int:
    parser = map_parser(__doc__, "profile_map.py")
    parser.add_argument("--keep", metavar="MAP.h5", help="keep the map here")
    args = parser.parse_args()
    exe = os.path.abspath(args.exe)
    work = tempfile.mkdtemp(prefix="profile-map-")
    out = os.path.join(work, "map.h5")
    store = ["periods", "rhs_evals"] + [f"{w}_{p}" for p in PHASES for w in ("t", "rhs")]
    sets = ["sweep.refine=0", "sweep.store=[" + ", ".join(f'"{q}"' for q in store) + "]"] + args.set
    mpi = mpi_prefix(args.ranks)
    command = [*mpi, exe, "sweep", args.scene, "-o", out, "--overwrite", "-q", "--format", "json"]
    for s in sets:
        command += ["--set", s]
    summary = json.loads(run(command).stdout)
    size = os.path.getsize(out)
    ns = ns_per_evaluation(exe)
    rate = disk_rate(work)

    with h5py.File(out, "r") as f:
        done = f["done"][...] != 0
        cls = classes_of(f)[done]
        wall = f["wall_s"][...][done]
        phase_s = {p: f[f"t_{p}"][...][done] for p in PHASES}
        phase_n = {p: f[f"rhs_{p}"][...][done].astype(float) for p in PHASES}
        evals = f["rhs_evals"][...][done].astype(float)
        periods = f["periods"][...][done].astype(float)
    if args.keep:
        shutil.copyfile(out, args.keep)
    shutil.rmtree(work)

    cells = int(done.sum())
    core_s = args.ranks * summary["wall_s"]
    cell_s = float(wall.sum())
    setup = cell_s - sum(float(v.sum()) for v in phase_s.values())
    output_s = summary["checkpoint_s"] + summary["final_checkpoint_s"]
    farm = core_s - cell_s - output_s
    print(f"map: {args.scene} with {', '.join(sets)}; {cells} cells on {args.ranks} ranks in "
          f"{summary['wall_s']:.3f} s ({summary['cells_per_s']:.1f} cells/s), {core_s:.3f} core-s")
    print(f"one evaluation: {ns:.1f} ns (rk4, 2^11 steps a period, Table 2); disk: {rate / 1e6:.0f} MB/s")
    print()
    print(f"{'phase':36} {'core-s':>9} {'share':>7} {'evals':>12} {'floor s':>10} {'ratio':>8}")
    rows = [("setup (wall_s less the phases)", setup, None)]
    rows += [(PHASE_NAMES[p], float(phase_s[p].sum()), float(phase_n[p].sum())) for p in PHASES]
    rows += [("output (checkpoints, final write)", output_s, "bytes"), ("the farm (ranks' wait, messages)", farm, None)]
    for name, seconds, n in rows:
        if n == "bytes":
            floor = size / rate
            evals_text = f"{size / 1e6:.1f} MB"
        elif n is None:
            floor, evals_text = None, "-"
        else:
            floor, evals_text = n * ns * 1e-9, f"{n:.3e}"
        ratio = f"{seconds / floor:8.1f}" if floor else f"{'-':>8}"
        floor_text = f"{floor:10.4f}" if floor is not None else f"{'-':>10}"
        print(f"{name:36} {seconds:9.3f} {seconds / core_s:7.1%} {evals_text:>12} {floor_text} {ratio}")
    print()
    print(f"{'cell class':14} {'cells':>7} {'core-s':>9} {'ms/cell':>9} {'evals/cell':>11} {'periods/cell':>13} "
          f"{'ns/eval':>8}")
    for name in ("no-contact", "periodic", "chatter", "non-periodic", "unresolved", "other"):
        m = cls == name
        if not m.any():
            continue
        n, s = int(m.sum()), float(wall[m].sum())
        # A class that evaluates nothing (no-contact cells decided in closed form) has no ns/eval.
        per_eval = f"{1e9 * s / evals[m].sum():8.1f}" if evals[m].sum() > 0 else f"{'-':>8}"
        print(f"{name:14} {n:7d} {s:9.3f} {1e3 * s / n:9.3f} {evals[m].mean():11.0f} {periods[m].mean():13.1f} "
              f"{per_eval}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
