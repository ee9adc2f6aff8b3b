"""vibromap.run in a loop against vibromap sweep (docs/benchmarks.md), from the checkout's root:

    PYTHONPATH=build/python /usr/bin/python3 tests/benchmarks/python_loop_vs_sweep.py [ROUNDS]

Side by side, alternately: `vibromap sweep` of 1000 cells on a line of E2 through Table 2 on
one rank (its own cells_per_s, start-up excluded) and a loop of 1000 vibromap.run calls over the
same E2 values (import excluded); then the loop on 1 and 2 threads, alternately. Medians of
ROUNDS (5). Works in a temporary folder."""
import concurrent.futures, json, os, statistics, subprocess, sys, tempfile, time
import numpy as np
import vibromap

EXE = os.path.abspath("build/vibromap")
ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 else 5
base = vibromap.Scene.from_toml("jobs/paper/table2.toml")
os.chdir(tempfile.mkdtemp(prefix="python-vs-sweep-"))
with open("line.toml", "w") as f:
    f.write(base.to_toml() + '\n[sweep]\n"contact.E2" = { from = 5e5, to = 5e6, n = 1000 }\n'
            'store = ["T_con", "k_con", "F_max", "z_ratio"]\n')
import h5py
subprocess.run([EXE, "sweep", "line.toml", "-o", "line.h5", "--overwrite", "-q"], check=True)
with h5py.File("line.h5") as f:
    E2 = [float(e) for e in f["E2"][...]]  # the sweep's own cell values


def one(e):
    return vibromap.run(base, **{"contact.E2": e}).k_con


def loop(threads):
    t = time.perf_counter()
    if threads == 1:
        k = [one(e) for e in E2]
    else:
        with concurrent.futures.ThreadPoolExecutor(threads) as pool:
            k = list(pool.map(one, E2))
    return len(k) / (time.perf_counter() - t), k


def sweep():
    p = subprocess.run([EXE, "sweep", "line.toml", "-o", "line.h5", "--overwrite", "-q", "--format", "json"],
                       capture_output=True, text=True, check=True)
    return json.loads(p.stdout)["cells_per_s"]


rates = {"sweep": [], "loop": [], "ratio": []}
for i in range(ROUNDS):
    s = sweep()
    l, k = loop(1)
    rates["sweep"].append(s); rates["loop"].append(l); rates["ratio"].append(l / s)
    print(f"round {i}: sweep {s:.1f} cells/s, loop {l:.1f} points/s, loop/sweep {l/s:.3f}", flush=True)
print("median: sweep {:.1f}, loop {:.1f}, loop/sweep {:.3f} (min {:.3f}, max {:.3f})".format(
    statistics.median(rates["sweep"]), statistics.median(rates["loop"]), statistics.median(rates["ratio"]),
    min(rates["ratio"]), max(rates["ratio"])))

# The loop's k_con equal the map's (same cells: the sweep's axis values are E2's).
with h5py.File("line.h5") as f:
    loop_k = np.array([np.nan if v is None else v for v in k])
    print("map k_con equal to the loop's, bit for bit:", np.array_equal(f["k_con"][...], loop_k, equal_nan=True))

speed = {1: [], 2: [], "ratio": []}
for i in range(ROUNDS):
    a, _ = loop(1)
    b, _ = loop(2)
    speed[1].append(a); speed[2].append(b); speed["ratio"].append(b / a)
    print(f"round {i}: 1 thread {a:.1f} points/s, 2 threads {b:.1f} points/s, 2/1 {b/a:.3f}", flush=True)
print("median: 1 thread {:.1f}, 2 threads {:.1f}, 2/1 {:.3f} (min {:.3f}, max {:.3f})".format(
    statistics.median(speed[1]), statistics.median(speed[2]), statistics.median(speed["ratio"]),
    min(speed["ratio"]), max(speed["ratio"])))
