#!/usr/bin/env python3
"""Which census attractor of each cell of a census line is the continued branch's orbit, and its family.

    branch_vs_census.py MAP.h5 BRANCH_UP.h5 BRANCH_DOWN.h5 [--tol 0.02]

MAP: a census line over the branch's key (`vibromap sweep`); BRANCH_UP / BRANCH_DOWN: `vibromap
continue ... -o` from the same start up and down the key. The stable part of branch 0 from its
start to where it loses stability or turns back (up: its period doubling at 8.2114 just below the
fold at 8.2420; down: its Neimark-Sacker point at 6.4015) is interpolated
at each cell's key value; the census attractor whose first period-start state lies nearest to
it (motion scales L = max(D, lambda F0 / k1), omega L) is the branch's, when nearer than --tol.
Prints one line per cell: key, the branch's attractor (index, regime, distance) and its family.
"""
import argparse
import sys

import h5py
import numpy as np

REGIMES = "periodic chatter no-contact permanent-contact quasi-periodic chaotic non-periodic unresolved failed".split()


def segment(path):
    """Branch 0's stable points from its start, up to where it loses stability or turns back."""
    with h5py.File(path, "r") as f:
        branch = f["point_branch"][:]
        p = f["param"][:][branch == 0]
        x = np.stack([f[v][:][branch == 0] for v in ("x1", "x2", "v1", "v2")], axis=1)
        stable = f["stable"][:][branch == 0]
    step = np.sign(p[1] - p[0])
    last = 0
    while last + 1 < len(p) and stable[last + 1] == 1 and np.sign(p[last + 1] - p[last]) == step:
        last += 1
    return p[: last + 1], x[: last + 1], stable[: last + 1], p[last]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map")
    ap.add_argument("up")
    ap.add_argument("down")
    ap.add_argument("--tol", type=float, default=0.02)
    a = ap.parse_args(argv)
    with h5py.File(a.map, "r") as f:
        axis = [k for k in f.keys() if f[k].attrs.get("key", b"") not in (b"", "")][0]
        w = f[axis][:]
        listed = f["attractors"][:]
        reg, n, k = f["attractor_regime"][:], f["attractor_n"][:], f["attractor_k"][:]
        first = f["attractor_strobe"][:][:, :, 0, :]
        fam = f["family"][:]
        flags = f["family_flags"][:]
        scene = f.attrs["scene"]
    L = 0.05  # Table 2: max(D, lambda F0 / k1) = max(0.05, 0.0127) m
    families = set()
    for branch in (a.up, a.down):
        p, x, stable, end = segment(branch)
        lo, hi = min(p[0], end), max(p[0], end)
        order = np.argsort(p)
        print(f"# {branch}: stable part from {p[0]:.4f} to {end:.4f}")
        for i, wi in enumerate(w):
            if not lo <= wi <= hi:
                continue
            state = np.array([np.interp(wi, p[order], x[order, j]) for j in range(4)])
            scale = np.array([L, L, wi * L, wi * L])
            d = np.linalg.norm((first[i, : listed[i]] - state) / scale, axis=1)
            d = np.where(np.isnan(d), np.inf, d)
            if len(d) == 0 or not np.isfinite(d.min()) or d.min() > a.tol:
                print(f"{wi:.3f}  no attractor within {a.tol} (nearest {d.min() if len(d) else np.inf:.3g})")
                continue
            j = int(np.argmin(d))
            label = f"({n[i, j]},{k[i, j]})" if reg[i, j] == 0 else REGIMES[reg[i, j]]
            families.add(int(fam[i, j]))
            print(f"{wi:.3f}  attractor {j} {label} at {d[j]:.2e}  family {fam[i, j]}  flags {flags[i, j]}")
    print(f"# families of the branch's attractors: {sorted(families)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
