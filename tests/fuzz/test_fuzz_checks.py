#!/usr/bin/env python3
"""The fuzzer's check of written HDF5 files (fuzz_run.nonfinite_in_h5) on made-up files with a
known answer: each must be flagged exactly where it holds a number the file does not declare.
And its count of the cells a scene asks for (fuzz_run.asked_cells: a sweep that large stopped by
the time bound with exit 3 is a large job, not a timeout), on scenes with a known count.

  tests/fuzz/test_fuzz_checks.py          # the ctest fuzz.checks; exit 0 when every case holds
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from fuzz_run import asked_cells, nonfinite_in_h5  # noqa: E402

NAN, INF = float("nan"), float("inf")


def branch(f, x1=(0.1, 0.2), strobe=(0.1, NAN), param=(7.0, 7.1)):
    f.attrs["title"] = "vibromap periodic-orbit branch"
    point = f.create_dataset("point", data=np.arange(len(param), dtype=np.int32))
    point.make_scale("point")
    f.create_dataset("param", data=np.array(param))
    f.create_dataset("x1", data=np.array(x1))
    f.create_dataset("strobe_x1", data=np.array(strobe))


def basins_with_nan_coordinate(f):
    f.attrs["title"] = "vibromap basins: the attractor of each initial state of a plane"
    x1 = f.create_dataset("x1", data=np.array([-1.0, NAN, 1.0]))
    x1.make_scale("x1")
    f.create_dataset("max_floquet", data=np.array([NAN]))


def map_with_fill(f):
    f.attrs["title"] = "vibromap regime map"
    f.create_dataset("k_con", data=np.array([NAN, 3.0]), fillvalue=NAN).attrs["_FillValue"] = NAN
    f.create_dataset("wall_s", data=np.array([NAN, 0.1]))  # no _FillValue: not declared


# (what, writer, the substrings the findings must have, in order; empty: nothing found)
CASES = (
    ("a branch with NaN only where it declares it", branch, []),
    ("a branch with NaN in x1", lambda f: branch(f, x1=(0.1, NAN)), ["x1: 1 NaN values"]),
    ("a branch with inf in strobe_x1", lambda f: branch(f, strobe=(INF, NAN)), ["strobe_x1: 1 inf values"]),
    ("a basins file with a NaN coordinate", basins_with_nan_coordinate, ["x1 (a coordinate): NaN"]),
    ("a map: NaN under a NaN _FillValue, and where none is declared", map_with_fill, ["wall_s: 1 NaN values"]),
    ("an inf attribute", lambda f: (branch(f), f.attrs.create("T", INF)), ["attribute /@T"]),
)


# (scene, the cells it asks for)
SCENES = (
    (b'[sweep]\nE1 = { from = 2e4, to = 2.1e11, n = 1e6, scale = "log" }\nE2 = { from = 1, to = 2, n = 3 }\n', 3e6),
    (b'[sweep]\nE1 = { values = [1.0, 2.0] }\nm2 = { from = 1, to = 2, n = 4 }\nstore = ["k_con"]\n', 8),
    (b'[system]\nm1 = 1.0\n', 0),           # no [sweep]
    (b'[sweep]\nE1 = { from = 1, to = \n', 0),  # not TOML
    (b'[sweep]\nE1 = { from = 1, to = 2, n = "x" }\n', 0),
)


def main():
    failures = 0
    for scene, cells in SCENES:
        got = asked_cells(scene)
        ok = got == cells
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} asked_cells of {scene[:50]!r}: {got} (expected {cells})")
    with tempfile.TemporaryDirectory() as d:
        for i, (what, write, expected) in enumerate(CASES):
            path = os.path.join(d, f"case{i}.h5")
            with h5py.File(path, "w") as f:
                write(f)
            found = nonfinite_in_h5(path)
            ok = len(found) == len(expected) and all(e in got for e, got in zip(expected, found))
            failures += not ok
            print(f"{'ok  ' if ok else 'FAIL'} {what}: found {found or 'nothing'}")
    total = len(CASES) + len(SCENES)
    print(f"test_fuzz_checks: {total - failures} of {total} cases as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
