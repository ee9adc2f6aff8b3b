"""Which of a map's labels brute force itself decides, and whether the map agrees there
(docs/benchmarks.md). From the checkout's root, with a built tree:

    /usr/bin/python3 tests/benchmarks/label_robustness.py [--exe build/vibromap] [--ranks 2]
        [--scene jobs/demo/e1_e2.toml] [--set KEY=VALUE ...] [--budget 10000]
        [--rtols 1e-9,1e-10,1e-11] [--map MAP.h5] [--keep DIR]

Makes the scene's coarse level (`sweep.refine = 0`) by brute force (`analysis.steady =
integrate`, `analysis.max_periods = BUDGET`) once at each of RTOLS, and the scene's default map
(or takes MAP.h5, a map of the same grid). A cell's label is its regime with (n, k). A cell is
robust where brute force gives one label at every tolerance, and that label is not
`unresolved`; elsewhere the label is a coin toss of the integration itself (a long chaotic
transient: which attractor it ends on, and when, moves with the rounding).

Prints the cells where the brute-force maps differ pair by pair, the robust cells, and where
the map differs from brute force on them (label against label, with counts); then the map's
labels on the coin-toss cells."""
import collections
import os
import shutil
import sys
import tempfile

import h5py
import numpy as np

from map_script import mpi_prefix, parser as map_parser, regime_names, run


def labels(path: str) -> np.ndarray:
    """Each cell's label, 'chaotic', '(3,3)', ... from the map's regime, n and k."""
    with h5py.File(path, "r") as f:
        names = regime_names(f)
        regime, n, k = (f[q][...].ravel().astype(int) for q in ("regime", "n", "k"))
    def label(r, nn, kk):
        name = names.get(r, str(r)).replace("_", "-")
        return f"({nn},{kk})" if name == "periodic" else f"{name}({nn},{kk})" if name == "chatter" else name
    return np.array([label(*c) for c in zip(regime, n, k)], dtype=object)


def counted(pairs) -> str:
    return ", ".join(f"{a} -> {b}: {c}" for (a, b), c in collections.Counter(pairs).most_common()) or "none"


def main() -> int:
    parser = map_parser(__doc__, "label_robustness.py")
    parser.add_argument("--budget", type=int, default=10000, help="brute force's analysis.max_periods")
    parser.add_argument("--rtols", default="1e-9,1e-10,1e-11", help="brute force's solver.rtol values")
    parser.add_argument("--map", help="the map to judge (default: the scene's default map, made here)")
    parser.add_argument("--keep", metavar="DIR", help="keep the maps made here in DIR")
    args = parser.parse_args()
    exe = os.path.abspath(args.exe)
    rtols = args.rtols.split(",")
    work = tempfile.mkdtemp(prefix="label-robustness-")
    mpi = mpi_prefix(args.ranks)

    def make(name, sets):
        out = os.path.join(work, name + ".h5")
        command = [*mpi, exe, "sweep", args.scene, "-o", out, "--overwrite", "-q"]
        for s in ["sweep.refine=0", *args.set, *sets]:
            command += ["--set", s]
        run("label_robustness", command)
        return out

    brute = {r: labels(make(f"brute_{r}", ["analysis.steady=integrate", f"analysis.max_periods={args.budget}",
                                          f"solver.rtol={r}"])) for r in rtols}
    judged = labels(args.map if args.map else make("default", []))
    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
        for name in os.listdir(work):
            shutil.copyfile(os.path.join(work, name), os.path.join(args.keep, name))
    shutil.rmtree(work)
    reference = brute[rtols[len(rtols) // 2]]
    if judged.shape != reference.shape:
        sys.exit(f"label_robustness: the map has {judged.size} cells, the scene's coarse level {reference.size}")

    print(f"brute force: {args.scene}, sweep.refine=0, analysis.max_periods={args.budget}, rtol {', '.join(rtols)}; "
          f"{reference.size} cells")
    for i, a in enumerate(rtols):
        for b in rtols[i + 1:]:
            d = brute[a] != brute[b]
            print(f"  rtol {a} against {b}: {int(d.sum())} labels differ ({counted(zip(brute[a][d], brute[b][d]))})")
    robust = np.logical_and.reduce([brute[r] == reference for r in rtols]) & (reference != "unresolved")
    print(f"robust cells (one label at every rtol, not unresolved): {int(robust.sum())}; the rest, coin tosses "
          f"or unresolved: {int((~robust).sum())}")
    d = robust & (judged != reference)
    print(f"the map against brute force on the robust cells: {int(d.sum())} differ "
          f"({counted(zip(judged[d], reference[d]))})")
    print(f"the map's labels on the rest: {counted((x, 'not decided') for x in judged[~robust])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
