"""Helpers shared by the campaign tests under mpiexec (sweep and multistart)."""
import os
import signal
import subprocess
import time

EXE = os.environ.get("VIBROMAP_EXE", "build/vibromap")
MPIEXEC = os.environ.get("VIBROMAP_MPIEXEC", "mpiexec")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


# The bistable point of the paper's Table 2 (docs/model.md): (1,1) soft in about half of the basin.
TABLE2_POINT = """
[system]
m2 = 310.0
omega2 = 3.606

[contact]
E1 = 1.4e10
E2 = 1e6
"""


# The paper's Table 2 (docs/model.md) solved by brute-force integration (not the default shooting):
# cells cost ~0.02-0.05 s each, so a sweep runs long enough to be stopped or killed mid-way.
def vibromap_stdout(*args, timeout=900):
    """`vibromap ARGS...` (any value str()-ed), which must succeed: its standard output."""
    done = subprocess.run([EXE, *map(str, args)], env=ENV, capture_output=True, text=True, timeout=timeout)
    assert done.returncode == 0, done.stderr
    return done.stdout


# A scene whose one orbit would take hours: an undamped chatter from v2 = 5 m/s, integrated for
# up to 10^8 periods; what a stop signal must interrupt in flight.
FOREVER = """
[system]
xi1 = 0.0
xi2 = 0.0

[initial]
v2 = 5.0

[solver]
max_steps = 10000000000

[analysis]
steady = "integrate"
max_periods = 100000000
"""

SLOW_SYSTEM = """
[system]
m2 = 310.0
omega2 = 3.606

[solver]
method = "dopri5"

[analysis]
steady = "integrate"
"""
# SLOW_SYSTEM with E1 x E2 axes.
SLOW_SCENE = SLOW_SYSTEM + """
[sweep]
E1 = {{ from = 2e4, to = 2.1e11, n = {n1}, scale = "log" }}
E2 = {{ from = 2e4, to = 2.1e11, n = {n2}, scale = "log" }}
store = ["T_con", "k_con", "F_max", "z_max", "periods"]
checkpoint_interval = {checkpoint}
progress_interval = {progress}
"""


def slow_scene(n1=4, n2=3, checkpoint=60.0, progress=0.5):
    """SLOW_SCENE's text for an n1 x n2 grid."""
    return SLOW_SCENE.format(n1=n1, n2=n2, checkpoint=checkpoint, progress=progress)


def descendants(pid):
    """Every process below pid (Open MPI puts each rank in a process group of its own)."""
    children = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        ppid = int(stat[stat.rindex(")") + 2:].split()[1])
        children.setdefault(ppid, []).append(int(entry))
    found, todo = [], [pid]
    while todo:
        for child in children.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def kill_all(pid):
    """SIGKILL mpiexec and every rank at once, as a cluster's time limit does."""
    for p in [pid, *descendants(pid)]:
        try:
            os.kill(p, signal.SIGKILL)
        except ProcessLookupError:
            pass


def wait_for_cells_done(proc, out, at_least, poll=0.1, timeout=120):
    """Polls the map `out` that a running sweep `proc` writes until /done counts `at_least`
    cells (or the sweep ends, or `timeout` s pass); returns the last count read."""
    import h5py  # only the tests that poll a map need it

    done = 0
    deadline = time.time() + timeout
    while time.time() < deadline and proc.poll() is None and done < at_least:
        time.sleep(poll)
        if not out.exists():
            continue
        try:
            with h5py.File(out, "r") as f:
                done = int(f["done"][()].sum())
        except (OSError, KeyError, ValueError, RuntimeError):
            continue  # the map is being written while we read it (no SWMR): try again
    return done


def reference_map(folder, scene_text):
    """A finished map of `scene_text` in `folder` (scene.toml, reference.h5): the undamaged
    reference the damage tests compare with."""
    scene = folder / "scene.toml"
    scene.write_text(scene_text)
    ref = folder / "reference.h5"
    proc = subprocess.run([EXE, "sweep", str(scene), "-o", str(ref), "-q"], env=ENV, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    return scene, ref


def journal_records(path):
    """How many intact start records the journal holds (io/journal.hpp's layout)."""
    import struct
    import zlib
    try:
        data = path.read_bytes()
    except OSError:
        return 0
    if len(data) < 16:
        return 0
    (length,) = struct.unpack_from("<Q", data, 8)
    pos, count = 16 + length + 4, 0
    while pos + 16 <= len(data):
        item, size = struct.unpack_from("<QQ", data, pos)
        end = pos + 16 + size
        if end + 4 > len(data):
            break
        (crc,) = struct.unpack_from("<I", data, end)
        if crc != zlib.crc32(data[pos:end]):
            break
        pos, count = end + 4, count + 1
    return count
