"""Every map quantity the program knows goes from the solver into the map and out of the Python
reader, named by the program (`vibromap keys`) and the file, never by a list kept here:

- a sweep storing all of them gives the same map on 1 and 2 ranks (rank 1's cells cross the
  wire, src/campaigns/sweep/cell_codec.cpp), each quantity a dataset with its units;
- read_map names each one, in the order stored, with the file's units and type;
- summarize_map finds every value of every cell done finite, but where the dataset's long_name
  says NaN means "not computed" (lyapunov here is computed nowhere);
- a quantity is 0 in no cell only where its long_name allows it (a phase of the solve that need
  not run), and the timings (long_name: "a timing") are the ones left out of the 1-vs-2 check.

Run by ctest (tests/campaigns/campaign_tests.cmake), which sets VIBROMAP_EXE and VIBROMAP_MPIEXEC.
"""
import pathlib
import subprocess
import sys

import h5py
import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(REPO / "postprocess"))
from campaign_helpers import ENV, EXE, MPIEXEC, vibromap_stdout  # noqa: E402

from vibromap import _summarize_map as summarize_map  # noqa: E402
from vibromap import _io as vibromap_h5  # noqa: E402

# Table 2 with the Flores law (jobs/demo/restitution_e2.toml) on 2 x 4 cells, all periodic with
# impacts, some Hertz-invalid, some clipped: every quantity but lyapunov (not asked) is not 0 in
# some cell.
SCENE = "jobs/demo/restitution_e2.toml"
# What a quantity's long_name says of it: a solve time (not the same on 1 and 2 ranks), and one
# of a phase of the solve (point_solver.hpp's PhaseTimes) that may have run in no cell here.
TIMING = "(a timing: differs run to run"
PHASE_NOT_RUN = "0 where the phase did not run)"
SETTINGS = ("sweep.restitution={values=[0.2,0.6]}", 'sweep.E2={from=2e4,to=2.1e11,n=4,scale="log"}')


def program_quantities():
    """The storable quantities as `vibromap keys --toml` lists them ("... any of T_con, k_con, ...")."""
    line = next(row for row in vibromap_stdout("keys", "--toml").splitlines() if row.startswith("# store = "))
    return [name.strip() for name in line.split("any of ", 1)[1].split(",")]


def sweep_storing(names, ranks, out):
    store = "sweep.store=[" + ",".join(f'"{name}"' for name in names) + "]"
    cmd = [MPIEXEC, "-n", str(ranks), EXE, "sweep", SCENE, "-o", str(out), "--quiet",
           *[a for s in (*SETTINGS, store) for a in ("--set", s)]]
    proc = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600, cwd=REPO)
    assert proc.returncode == 0, proc.stderr


def test_every_quantity_reaches_the_map_and_the_reader(tmp_path):
    names = program_quantities()
    assert len(names) >= 15 and "hertz_valid" in names and "lyapunov" in names
    maps = {ranks: tmp_path / f"map{ranks}.h5" for ranks in (1, 2)}
    for ranks, out in maps.items():
        sweep_storing(names, ranks, out)
    with h5py.File(maps[1], "r") as one, h5py.File(maps[2], "r") as two:
        assert two["done"][()].all()
        long_names = {name: str(two[name].attrs["long_name"]) for name in names}
        for name in ("status", "regime", "n", "k", "soft", *names):
            if TIMING not in long_names.get(name, ""):
                np.testing.assert_array_equal(one[name][()], two[name][()], err_msg=name)
        units = {name: two[name].attrs["units"] for name in names}
        kinds = {name: two[name].dtype for name in names}
    sweep = vibromap_h5.read_map(str(maps[2]))
    assert sweep.stored == names
    for name in names:
        assert sweep.data[name].shape == (2, 4), name
        assert sweep.data[name].dtype == kinds[name] and kinds[name] in (np.int64, np.float64), name
        assert sweep.units[name] == units[name] != "", name
        assert sweep.long_names[name], name
    # A quantity lost on the way reads as a default record's 0 (or NaN) in every cell.
    not_computed = sweep.not_computed_as_nan()
    assert "lyapunov" in not_computed and "T_con" not in not_computed
    for name in names:
        if name not in not_computed and not long_names[name].endswith(PHASE_NOT_RUN):
            assert (sweep.data[name] != 0).any(), name
    # The phases' times make up part of each cell's solve time; classification runs in every cell.
    phases = sum(sweep.data[name] for name in names if TIMING in long_names[name])
    assert (sweep.data["t_classify"] > 0).all() and (phases <= sweep.data["wall_s"]).all()
    assert np.isnan(sweep.data["lyapunov"]).all()  # analysis.lyapunov is off: computed nowhere
    lines, bad = summarize_map.summary_lines(sweep, slowest=0)
    assert bad == 0, lines
    assert "finite: every float quantity of every computed cell" in lines
