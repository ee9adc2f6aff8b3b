"""Ctrl-C in Python (docs/benchmarks.md): how long from SIGINT to KeyboardInterrupt, from the
checkout's root:

    PYTHONPATH=build/python /usr/bin/python3 tests/benchmarks/python_ctrl_c.py [ROUNDS]

A child Python runs a long call and prints a line the moment the KeyboardInterrupt reaches it;
this script sends SIGINT once the call is under way and times until that line. Calls:
  - `vibromap.run` of a point of minutes (Table 2 with rk4 at 10^7 steps a period), signalled
    0.5 s into the solve;
  - `vibromap.sweep` of a 4000-cell map on 1 rank and on 2 (mpirun), signalled once the farm
    reports cells done; then the map must be whole: vibromap.files.open reads it, no lock left.
Medians of ROUNDS (5), with min and max. Works in a temporary folder."""
import os, signal, statistics, subprocess, sys, tempfile, time

import vibromap
import vibromap.files

ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 else 5
TOP = os.path.abspath(".")
TABLE2 = os.path.join(TOP, "jobs", "paper", "table2.toml")
os.environ.setdefault("VIBROMAP_EXE", os.path.join(TOP, "build", "vibromap"))
work = tempfile.mkdtemp(prefix="python-ctrl-c-")

CHILD = """
import sys, time, vibromap
scene = vibromap.Scene.from_toml(sys.argv[1])
try:
    if sys.argv[2] == "run":
        print("started", flush=True)
        vibromap.run(scene, **{"solver.method": "rk4", "solver.rk4_steps": 10_000_000, "solver.max_steps": 10**10})
    else:
        vibromap.sweep(scene, ranks=int(sys.argv[2]), output=sys.argv[3], overwrite=True)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
"""
with open(os.path.join(work, "map.toml"), "w") as f:
    f.write(vibromap.Scene.from_toml(TABLE2).to_toml()
            + '\n[sweep]\n"contact.E2" = { from = 5e5, to = 5e6, n = 1000 }\n"forcing.omega" = { from = 6, to = 8, n = 4 }\n')


def once(what: str) -> float:
    out = os.path.join(work, f"map_{what}.h5")
    args = [sys.executable, "-c", CHILD, TABLE2 if what == "run" else os.path.join(work, "map.toml"), what, out]
    child = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    try:
        if what == "run":
            assert child.stdout.readline() == "started\n"
            time.sleep(0.5)
        else:
            for line in child.stderr:  # the farm's progress lines, passed on by the call
                if line.startswith("sweep: ") and not line.startswith("sweep: 0/"):
                    break
        sent = time.perf_counter()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline()
        latency = time.perf_counter() - sent
        child.communicate(timeout=60)
    finally:
        child.kill()
    assert line == "KeyboardInterrupt\n", line
    if what != "run":
        assert not os.path.exists(out + ".lock"), "a lock left"
        ds = vibromap.files.open(out)  # whole: it opens, checked in full
        done = int((ds.done != 0).sum())
        assert 0 < done < ds.done.size, done
    return latency


for what, name in (("run", "run, Table 2 rk4 10^7 steps/T"), ("1", "sweep, 1 rank"), ("2", "sweep, 2 ranks")):
    t = [once(what) for _ in range(ROUNDS)]
    print(f"{name}: SIGINT to KeyboardInterrupt median {statistics.median(t):.3f} s (min {min(t):.3f}, "
          f"max {max(t):.3f}, {ROUNDS} rounds)", flush=True)
