"""Runs one fuzz case (fuzz_cases.py) in a scratch directory of its own, bounded in time and
memory, and judges what happened: the exit code, the messages, the files written or left,
the canaries, the numbers in the outputs.

Problems are (tag, detail) pairs; the tags are the failure classes of the report:
  timeout          still running at the time bound; SIGTERM then ended it (not a failure for a
                   sweep of LARGE_CELLS cells or more that SIGTERM stopped with exit 3)
  hang             still running at the time bound and SIGTERM did not end it within the bound
  memory           peak resident memory above the bound (the run is killed when it gets there)
  crash            died of a signal the fuzzer did not send (SIGSEGV, SIGABRT, ...)
  exit-1           exit code 1: an internal error, a bug by the exit-code table
  exit-code        an exit code outside 0, 2, 3, 4
  stderr           a failed command's stderr is not exactly one line 'vibromap: error: ...'
  stdout-on-error  a failed command wrote on stdout
  expected-exit    the case has a required exit code (a hostile output, a non-file scene) and
                   the run ended with another (0: the hostile thing was accepted)
  slow-refusal     a refusal required at once came after the quick bound
  wrote-on-exit-2  exit 2 and a file was created or changed in the scratch directory
  changed-on-exit-4 exit 4 and a file that existed before was changed
  deleted          a path that existed before the run is gone
  canary           a canary (a link's target, a node, a directory, a link) changed, or a path
                   that must stay absent was created (through a dangling link)
  leak             a lock, journal or temporary file left behind, or a file left by exit 4
  bad-json         exit 0 with --format json and stdout is not JSON
  nonfinite-json   NaN or Infinity in JSON output
  nonfinite-h5     inf anywhere in a written HDF5 file (datasets, attributes), NaN in a coordinate,
                   or NaN in a dataset its kind of file does not declare NaN in (NAN_FOR_MISSING,
                   from docs/file-formats.md)
  bad-h5           exit 0 and a written HDF5 file cannot be read
  nonfinite-csv    inf in a written CSV file
  nonfinite-table  inf in a table on stdout
  slow-stop        signal class: not ended within the bound after SIGTERM or SIGINT
  no-checkpoint    signal class: a checkpointing command died of the signal instead of exit 3
  damage-accepted  damage class: a damaged map resumed (or summarized) with success and its
                   content differs from the intact map's
  traceback        a Python traceback from the postprocess
  setup            the case could not be prepared (reported, not a vibromap failure)
"""
import hashlib
import json
import os
import re
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
import tomllib
from dataclasses import dataclass, field

from fuzz_cases import CANARY_DIR, POSTPROCESS_SCRIPTS, SCENE, STOPS_WITH_EXIT_3

# The postprocess's readers and test helpers: a changed format version (stamp.set_version) and the
# line that refuses it (vibromap._io.h5io.version_refusal).
POSTPROCESS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "postprocess")
sys.path[:0] = [POSTPROCESS, os.path.join(POSTPROCESS, "tests")]

EXIT_ALLOWED = (0, 2, 3, 4)


@dataclass
class Limits:
    timeout: float = 20.0        # s per case
    memory_mb: float = 500.0     # peak resident memory
    signal_bound: float = 3.0    # s from a signal to the end of the run
    quick_bound: float = 5.0     # s for a refusal required at once


@dataclass
class RunResult:
    rc: int = None               # exit code, or None when killed by a signal
    signum: int = None           # the signal that ended the run
    wall: float = 0.0
    maxrss_mb: float = 0.0
    stdout: bytes = b""
    stderr: bytes = b""
    timed_out: bool = False      # still running at the time bound
    ignored_term: bool = False   # ... and SIGTERM did not end it
    mem_killed: bool = False
    signal_sent: float = None    # when the case's own signal was sent (s from the start)
    killed_after_signal: bool = False  # ... and the run was still going signal_bound s later
    after_signal: float = None   # s from that signal to the end


@dataclass
class Outcome:
    case: object
    argv: list
    result: RunResult
    problems: list = field(default_factory=list)
    scratch: str = ""


# ---- the scratch directory ---------------------------------------------------------------

def make_setup(scratch, setup, shared):
    """Makes the case's files; `shared` maps names of shared files (the damage class's
    intact map) to (path, attribute byte ranges)."""
    for s in setup:
        path = os.path.join(scratch, s.name)
        if s.kind in ("file", "dir", "symlink", "fifo", "device", "sparse", "copy") and os.path.dirname(s.name):
            os.makedirs(os.path.dirname(path), exist_ok=True)
        if s.kind == "file":
            with open(path, "wb") as f:
                f.write(s.data)
        elif s.kind == "dir":
            os.makedirs(path, exist_ok=True)
        elif s.kind == "symlink":
            os.symlink(s.data.decode(), path)
        elif s.kind == "fifo":
            os.mkfifo(path)
        elif s.kind == "device":
            os.mknod(path, 0o666 | stat.S_IFCHR, os.makedev(1, 3))   # a /dev/null node
        elif s.kind == "sparse":
            with open(path, "wb") as f:
                f.truncate(int(s.data))
        elif s.kind == "chmod000":
            os.chmod(path, 0)
        elif s.kind == "copy":
            shutil.copyfile(shared[s.data.decode()][0], path)
        elif s.kind == "flip":
            flip_bytes(path, eval(s.data.decode()), shared["damage-map"][1])  # a repr of a list of tuples
        elif s.kind == "version":  # the map's format version changed in place
            from stamp import set_version
            set_version(path, eval(s.data.decode()))


def flip_bytes(path, flips, regions):
    """Flips one bit per (in_attributes, fraction, bit): at `fraction` of the file, or of the
    byte ranges where the intact map keeps its attributes' text."""
    with open(path, "r+b") as f:
        data = bytearray(f.read())
        for in_attr, fraction, bit in flips:
            if in_attr and regions:
                total = sum(b - a for a, b in regions)
                at = int(fraction * total)
                for a, b in regions:
                    if at < b - a:
                        offset = a + at
                        break
                    at -= b - a
            else:
                offset = int(fraction * len(data))
            data[min(offset, len(data) - 1)] ^= 1 << bit
        f.seek(0)
        f.write(data)


def file_digest(path, size):
    if size > (64 << 20):
        return "large"
    try:
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return "unreadable"


def snapshot(scratch):
    """Every path under the scratch directory (links not followed): kind, content digest (a
    regular file), link target, device number. A file opened for writing and left as it was
    (HDF5 rewrites its superblock flags on open) counts as unchanged."""
    entries = {}
    for root, dirs, files in os.walk(scratch):
        for name in dirs + files:
            path = os.path.join(root, name)
            try:
                st = os.lstat(path)
            except OSError:
                continue
            rel = os.path.relpath(path, scratch)
            kind = stat.S_IFMT(st.st_mode)
            link = os.readlink(path) if stat.S_ISLNK(st.st_mode) else ""
            digest = file_digest(path, st.st_size) if stat.S_ISREG(st.st_mode) else ""
            entries[rel] = (kind, digest, link, st.st_rdev)
    return entries


def describe(scratch, rel):
    """What a canary is: its kind and its content (a file's bytes, a link's target, a
    directory's listing, a node's device number); None when absent."""
    path = os.path.join(scratch, rel)
    try:
        st = os.lstat(path)
    except OSError:
        return None
    if stat.S_ISLNK(st.st_mode):
        return ("link", os.readlink(path))
    if stat.S_ISREG(st.st_mode):
        with open(path, "rb") as f:
            return ("file", hashlib.sha256(f.read()).hexdigest(), st.st_ino)
    if stat.S_ISDIR(st.st_mode):
        return ("dir", tuple(sorted(os.listdir(path))), st.st_ino)
    return ("node", stat.S_IFMT(st.st_mode), st.st_rdev, st.st_ino)


def remove_scratch(scratch):
    for root, dirs, _ in os.walk(scratch):
        for d in dirs:
            try:
                os.chmod(os.path.join(root, d), 0o755)
            except OSError:
                pass
    shutil.rmtree(scratch, ignore_errors=True)


# ---- running -----------------------------------------------------------------------------

def rss_mb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return 0.0


def catches(pid, sig) -> bool:
    """Whether process pid has a handler of its own for sig (its SigCgt mask in /proc); True when
    that cannot be read."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (sig - 1) & 1)
    except (OSError, ValueError, IndexError):
        pass
    return True


# A case's signal waits, after its time, until the process has its own handler for it (a signal
# before the program's first instruction, while the loader maps its libraries, kills any
# program), but no longer than this many seconds.
SIGNAL_HANDLER_WAIT = 2.0


def kill_group(pid, sig):
    try:
        os.killpg(pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def run_bounded(argv, cwd, env, limits, case_signal=()):
    """Runs argv in its own session, stdin from /dev/null, stdout and stderr to files; kills it
    at the memory bound; at the time bound sends SIGTERM, then SIGKILL after signal_bound s."""
    res = RunResult()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        proc = subprocess.Popen(argv, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                start_new_session=True)
        deadline_kill = None
        status, usage = None, None
        next_rss = 0.0
        while True:
            pid, st, ru = os.wait4(proc.pid, os.WNOHANG)
            if pid == proc.pid:
                status, usage = st, ru
                break
            now = time.monotonic() - start
            if now >= next_rss:
                if rss_mb(proc.pid) > limits.memory_mb:
                    res.mem_killed = True
                    kill_group(proc.pid, signal.SIGKILL)
                next_rss = now + 0.03
            if (case_signal and res.signal_sent is None and now >= case_signal[1]
                    and (catches(proc.pid, getattr(signal, case_signal[0]))
                         or now >= case_signal[1] + SIGNAL_HANDLER_WAIT)):
                res.signal_sent = now
                kill_group(proc.pid, getattr(signal, case_signal[0]))
                deadline_kill = now + limits.signal_bound
            if not res.timed_out and now >= limits.timeout:
                res.timed_out = True
                kill_group(proc.pid, signal.SIGTERM)
                deadline_kill = now + limits.signal_bound
            if deadline_kill is not None and now >= deadline_kill:
                if res.timed_out:
                    res.ignored_term = True
                else:
                    res.killed_after_signal = True
                kill_group(proc.pid, signal.SIGKILL)
                deadline_kill = float("inf")
            time.sleep(0.005 if now < 1.0 else 0.02)
        proc.returncode = os.waitstatus_to_exitcode(status)
        res.wall = time.monotonic() - start
        kill_group(proc.pid, signal.SIGKILL)   # anything the run left in its session
        if os.WIFSIGNALED(status):
            res.signum = os.WTERMSIG(status)
        else:
            res.rc = os.WEXITSTATUS(status)
        res.maxrss_mb = usage.ru_maxrss / 1024.0
        if res.signal_sent is not None:
            res.after_signal = res.wall - res.signal_sent
        out.seek(0)
        err.seek(0)
        res.stdout, res.stderr = out.read(), err.read()
    return res


# ---- the checks --------------------------------------------------------------------------

INF_WORD = re.compile(r"(?<![\w.])[-+]?inf(inity)?(?![\w])", re.IGNORECASE)


def reject_constant(name):
    raise ValueError(f"non-finite JSON number {name}")


def check_json(text, problems):
    try:
        json.loads(text, parse_constant=reject_constant)
    except ValueError as exc:
        tag = "nonfinite-json" if "non-finite" in str(exc) else "bad-json"
        problems.append((tag, str(exc)[:200]))


# The datasets each kind of file declares NaN in, as docs/file-formats.md gives them: "not
# computed", "not listed", "beyond the period", "no contact", "undefined". Keyed by the file's root
# `title`; names are fnmatch patterns of the dataset's path. A regime map's float datasets declare
# it by their _FillValue (NaN where done == 0; the quantities "(NaN where not computed)"). Every
# other float dataset, and every coordinate of every file, must hold finite numbers only.
NAN_FOR_MISSING = {
    "vibromap basins": ("strobe", "max_floquet"),
    "vibromap periodic-orbit branch": ("strobe_x1",),
    "vibromap curves": ("curve_*/T_con", "curve_*/k_con", "curve_*/z_ratio", "curve_*/F_max"),
    "vibromap orbit diagram": ("x1", "x2", "v1", "v2"),
    "vibromap multistart optimisation": ("seed_objective", "starts/*/objective", "starts/*/value", "starts/*/k_con",
                                         "starts/*/T_con", "starts/*/F_max", "starts/*/max_multiplier",
                                         "starts/*/z_ratio", "starts/*/soft_fraction", "best/*/soft_check/*"),
}


def nan_declared(kind, name, obj):
    """Whether the file of this kind (its title) declares NaN as 'missing' in dataset `name`."""
    import fnmatch
    import numpy as np
    fill = obj.attrs.get("_FillValue")
    if fill is not None and np.asarray(fill).dtype.kind == "f" and np.isnan(np.asarray(fill)).all():
        return True
    patterns = next((v for k, v in NAN_FOR_MISSING.items() if kind.startswith(k)), ())
    return any(fnmatch.fnmatchcase(name, p) for p in patterns)


def nonfinite_in_h5(path):
    """Non-finite numbers of an HDF5 file: inf anywhere (datasets and attributes); NaN in a
    coordinate (a dimension scale), or in a dataset the file does not declare NaN in
    (NAN_FOR_MISSING)."""
    import h5py
    import numpy as np
    found = []

    def attrs(obj, where):
        for name, value in obj.attrs.items():
            a = np.asarray(value)
            if a.dtype.kind == "f" and np.isinf(a).any():
                found.append(f"attribute {where}@{name} = {a.ravel()[:4]}")

    def visit(name, obj):
        attrs(obj, name)
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
            data = obj[()]
            if np.isinf(data).any():
                found.append(f"{name}: {int(np.isinf(data).sum())} inf values")
            elif h5py.h5ds.is_scale(obj.id) and np.isnan(data).any():
                found.append(f"{name} (a coordinate): NaN")
            elif np.isnan(data).any() and not nan_declared(kind, name, obj):
                found.append(f"{name}: {int(np.isnan(data).sum())} NaN values (the file declares no NaN there)")

    with h5py.File(path, "r") as f:
        title = f.attrs.get("title", "")
        kind = title.decode(errors="replace") if isinstance(title, bytes) else str(title)
        attrs(f, "/")
        f.visititems(visit)
    return found


def check_outputs(scratch, before, after, outcome):
    """Exit 0: every new or changed .h5 and .csv file holds finite numbers; stdout too."""
    problems, case = outcome.problems, outcome.case
    for rel, entry in after.items():
        if entry[0] != stat.S_IFREG or before.get(rel) == entry or rel.startswith(CANARY_DIR + "/"):
            continue
        path = os.path.join(scratch, rel)
        with open(path, "rb") as f:
            is_hdf5 = f.read(8) == b"\x89HDF\r\n\x1a\n"
        if is_hdf5:
            try:
                bad = nonfinite_in_h5(path)
            except Exception as exc:  # an unreadable output
                problems.append(("bad-h5", f"{rel}: {type(exc).__name__}: {str(exc)[:150]}"))
                continue
            if bad:
                problems.append(("nonfinite-h5", f"{rel}: " + "; ".join(bad[:3])))
        elif rel.endswith(".csv") or case.draft.command == "accuracy":
            with open(path, errors="replace") as f:
                m = INF_WORD.search(f.read())
            if m:
                problems.append(("nonfinite-csv", f"{rel}: '{m.group(0)}'"))
    text = outcome.result.stdout.decode(errors="replace")
    # A help option anywhere (CLI11 also takes `--help=1`) prints help, not the JSON asked for.
    asks_help = any(a in ("-h", "--help") or a.startswith("--help=") for a in outcome.argv)
    if case.draft.json and case.draft.command not in POSTPROCESS_SCRIPTS and not asks_help:
        check_json(text, problems)
    elif INF_WORD.search(text):
        problems.append(("nonfinite-table", INF_WORD.search(text).group(0)))


def first_lines(data, n=2):
    return " | ".join(data.decode(errors="replace").strip().splitlines()[:n])[:300]


# A sweep this large cannot end within the time bound (about 1,000 cells/s a core): a mutation
# that asks for it (n = 2 scaled by 1e6) is a large job, and its SIGTERM stop with exit 3 is right.
LARGE_CELLS = 50_000


def asked_cells(scene):
    """The cells a scene's [sweep] asks for (the product of its axes' n or values), 0 when the
    scene has no readable [sweep]."""
    try:
        sweep = tomllib.loads(scene.decode()).get("sweep", {})
        cells = 1
        axes = 0
        for value in sweep.values():
            if isinstance(value, dict) and "n" in value:
                cells *= float(value["n"])
            elif isinstance(value, dict) and isinstance(value.get("values"), list):
                cells *= len(value["values"])
            else:
                continue
            axes += 1
        return cells if axes else 0
    except (ValueError, TypeError, UnicodeDecodeError, AttributeError, OverflowError):
        return 0


def check_exit(outcome, limits):
    """Exit code, signal, time, memory and messages."""
    res, draft, problems = outcome.result, outcome.case.draft, outcome.problems
    if res.mem_killed or res.maxrss_mb > limits.memory_mb:
        problems.append(("memory", f"peak RSS {res.maxrss_mb:.0f} MB > {limits.memory_mb:.0f} MB"
                         + (" (killed)" if res.mem_killed else "")))
    if res.timed_out:
        if (not res.ignored_term and res.rc == 3 and draft.command in STOPS_WITH_EXIT_3
                and asked_cells(draft.scene) >= LARGE_CELLS):
            return  # a large map the scene asked for, stopped with its checkpoint: what SIGTERM is for
        if res.ignored_term:
            problems.append(("hang", f"still running after {limits.timeout:.0f} s and SIGTERM did not end it"))
        else:
            problems.append(("timeout", f"still running after {limits.timeout:.0f} s (SIGTERM ended it: "
                             f"{'signal ' + str(res.signum) if res.rc is None else 'exit ' + str(res.rc)})"))
    if res.signum is not None and not res.timed_out and not res.mem_killed and res.signal_sent is None:
        problems.append(("crash", f"died of signal {res.signum} ({signal.Signals(res.signum).name}): {first_lines(res.stderr)}"))
    if draft.command in POSTPROCESS_SCRIPTS:  # their own exit codes: check_damage
        return
    if res.rc == 1:
        problems.append(("exit-1", first_lines(res.stderr)))
    elif res.rc is not None and res.rc not in EXIT_ALLOWED:
        problems.append(("exit-code", f"exit {res.rc}: {first_lines(res.stderr)}"))
    if res.rc in (1, 2, 4) and not res.timed_out:
        lines = res.stderr.decode(errors="replace").splitlines()
        if len(lines) != 1 or not lines[0].startswith("vibromap: error: ") or not res.stderr.endswith(b"\n"):
            problems.append(("stderr", f"{len(lines)} lines: {first_lines(res.stderr, 3)}"))
        if res.stdout:
            problems.append(("stdout-on-error", first_lines(res.stdout)))
    if draft.expect and not res.timed_out and not res.mem_killed and res.rc not in draft.expect:
        got = f"exit {res.rc}" if res.rc is not None else f"signal {res.signum}"
        problems.append(("expected-exit", f"{got}, expected {draft.expect_why}"))
    if draft.quick and res.rc in draft.expect and res.wall > limits.quick_bound:
        problems.append(("slow-refusal", f"refused after {res.wall:.1f} s"))


def check_signal(outcome, limits):
    res, draft, problems = outcome.result, outcome.case.draft, outcome.problems
    if res.signal_sent is None:
        return
    if res.killed_after_signal:
        problems.append(("slow-stop", f"{draft.signal[0]} at {res.signal_sent:.2f} s did not end the run "
                         f"within {limits.signal_bound:.0f} s (killed)"))
    elif res.signum == getattr(signal, draft.signal[0]) and draft.command in STOPS_WITH_EXIT_3:
        problems.append(("no-checkpoint", f"died of {signal.Signals(res.signum).name} instead of exit 3"))


def check_files(scratch, before, after, outcome):
    """What the run created, changed, deleted or left."""
    res, problems = outcome.result, outcome.problems
    added = sorted(set(after) - set(before))
    removed = sorted(set(before) - set(after))
    changed = sorted(r for r in set(before) & set(after)
                     if before[r] != after[r] and before[r][0] != stat.S_IFDIR)
    if removed:
        problems.append(("deleted", ", ".join(removed[:5])))
    if res.rc == 2:  # a file the one error line says is kept (the optimiser's seeding map) is no write
        line = res.stderr.decode(errors="replace")
        added = [r for r in added if not (os.path.basename(r) in line and " kept" in line)]
    if res.rc == 2 and (added or changed):
        problems.append(("wrote-on-exit-2", "new: " + ", ".join(added[:5]) + "; changed: " + ", ".join(changed[:5])))
    if res.rc == 4 and changed:
        problems.append(("changed-on-exit-4", ", ".join(changed[:5])))
    leaks = []
    for rel in added:
        name = os.path.basename(rel)
        if after[rel][0] == stat.S_IFDIR:
            continue
        if res.rc == 4 or name.endswith(".lock") or name.startswith(".") or "tmp" in name.lower() or name.endswith("~"):
            leaks.append(rel)
        elif name.endswith(".journal") and res.rc != 3:
            leaks.append(rel)
        elif res.rc == 0 and not (name.endswith(".h5") or name.endswith(".csv")):
            leaks.append(rel)
    if leaks and res.rc in EXIT_ALLOWED and not res.timed_out:
        problems.append(("leak", ", ".join(leaks[:5])))


def check_canaries(scratch, draft, canary_before, problems):
    for rel, was in canary_before.items():
        now = describe(scratch, rel)
        if now != was:
            problems.append(("canary", f"{rel}: {was[0] if was else 'absent'} -> {now[0] if now else 'absent'}"
                             + (" (content changed)" if was and now and was[0] == now[0] else "")))
    for rel in draft.absent:
        if os.path.lexists(os.path.join(scratch, rel)):
            problems.append(("canary", f"{rel} was created through a dangling link"))


def map_content(path):
    """What of a map must survive damage, by name: every attribute and every dataset's
    values (wall_s aside, a timing), each as a digest; None when the file cannot be read."""
    import h5py
    import numpy as np
    content = {}

    def digest(data):
        return hashlib.sha256(data).hexdigest()[:16]

    def attrs(obj, where):
        for name in obj.attrs:
            content[f"{where}@{name}"] = digest(repr(np.asarray(obj.attrs[name]).tolist()).encode())

    def visit(name, obj):
        attrs(obj, name)
        if isinstance(obj, h5py.Dataset) and name != "wall_s":
            content[name] = digest(np.ascontiguousarray(obj[()]).tobytes())
    try:
        with h5py.File(path, "r") as f:
            attrs(f, "")
            f.visititems(visit)
    except Exception:
        return None
    return content


def content_differs(path, intact):
    """What differs between the map at path and the intact map's content (empty: nothing)."""
    now = map_content(path)
    if now is None:
        return ["the file cannot be read with h5py"]
    return sorted(k for k in set(now) | set(intact) if now.get(k) != intact.get(k))


def check_damage(scratch, outcome, shared):
    res, draft, problems = outcome.result, outcome.case.draft, outcome.problems
    if "Traceback" in res.stderr.decode(errors="replace"):
        problems.append(("traceback", first_lines(res.stderr.splitlines()[-1] if res.stderr else b"")))
        return
    version = [s for s in draft.setup if s.kind == "version"]
    if version:  # refused in the one line vibromap prints for it, naming both versions
        from vibromap._io.h5io import version_refusal
        found = eval(version[0].data.decode())
        prog = "vibromap" if draft.post == "resume" else draft.command
        line = f"{prog}: error: {version_refusal('map.h5', 'regime map', 0 if found is None else found)}\n"
        if res.stderr.decode(errors="replace") != line:
            problems.append(("stderr", f"expected {line!r}, got {first_lines(res.stderr, 3)}"))
        return
    intact = shared["damage-map"][2]
    path = os.path.join(scratch, "map.h5")
    if draft.post == "resume" and res.rc == 0:
        differs = content_differs(path, intact)
        if differs:
            problems.append(("damage-accepted", f"sweep --resume exit 0 and the map differs from the intact one "
                             f"in {', '.join(differs[:6])}"))
    elif draft.post in POSTPROCESS_SCRIPTS:
        # The postprocess must refuse a map whose file attributes (title, Conventions,
        # vibromap_version, identity, ...) are damaged; a damaged chunk of a dataset it does not
        # read is no concern of a summary, so only the root attributes are compared here.
        differs = [d for d in content_differs(path, intact) if d.startswith("@") or "h5py" in d] if res.rc in (0, 1) else []
        if differs:
            problems.append(("damage-accepted", f"{draft.command} exit {res.rc} on a map that differs from the "
                             f"intact one in {', '.join(differs[:6])}: {first_lines(res.stdout, 1)}"))
        if res.rc == 2 and not res.stderr.decode(errors="replace").startswith(f"{draft.command}: error: "):
            problems.append(("stderr", first_lines(res.stderr, 3)))
        if res.rc == 2 and len(res.stderr.decode(errors="replace").splitlines()) != 1:
            problems.append(("stderr", f"{draft.command}: not one line: {first_lines(res.stderr, 3)}"))
        if res.rc not in ((0, 1, 2) if draft.command == "summarize_map" else (0, 2)):
            problems.append(("exit-code", f"{draft.command} exit {res.rc}"))


# ---- one case ----------------------------------------------------------------------------

def case_argv(case, exe, repo):
    draft = case.draft
    if draft.command in POSTPROCESS_SCRIPTS:
        script = [os.path.join(repo, "postprocess", "vibromap-post"), draft.command, "map.h5"]
        return script if draft.command == "summarize_map" else script + ["-o", "picture.png"]
    return [exe] + draft.args


def run_case(case, exe, repo, env, limits, workdir, shared, keep=False):
    """Runs `case` in a new scratch directory under `workdir`; returns its Outcome."""
    scratch = tempfile.mkdtemp(prefix=f"case{case.index:05d}-", dir=workdir)
    draft = case.draft
    argv = case_argv(case, exe, repo)
    outcome = Outcome(case=case, argv=argv, result=RunResult(), scratch=scratch)
    try:
        if SCENE in draft.args:
            with open(os.path.join(scratch, SCENE), "wb") as f:
                f.write(draft.scene)
        make_setup(scratch, draft.setup, shared)
    except Exception as exc:
        outcome.problems.append(("setup", f"{type(exc).__name__}: {exc}"))
        return outcome
    canary_before = {rel: describe(scratch, rel) for rel in draft.canaries}
    before = snapshot(scratch)
    env = dict(env, TMPDIR=os.path.join(env["TMPDIR"], os.path.basename(scratch)))  # Open MPI's session files
    os.makedirs(env["TMPDIR"], exist_ok=True)
    outcome.result = run_bounded(argv, scratch, env, limits, draft.signal)
    shutil.rmtree(env["TMPDIR"], ignore_errors=True)
    after = snapshot(scratch)
    check_exit(outcome, limits)
    check_signal(outcome, limits)
    if draft.command in POSTPROCESS_SCRIPTS or draft.post:
        check_damage(scratch, outcome, shared)
    if draft.command not in POSTPROCESS_SCRIPTS:
        check_files(scratch, before, after, outcome)
    check_canaries(scratch, draft, canary_before, outcome.problems)
    if outcome.result.rc == 0 and draft.command not in POSTPROCESS_SCRIPTS:
        check_outputs(scratch, before, after, outcome)
    if not keep:
        remove_scratch(scratch)
    return outcome


# ---- reproducing -------------------------------------------------------------------------

def setup_shell(setup, case_dir):
    """Shell lines that make a case's files (scene content from the saved copy)."""
    lines = []
    for s in setup:
        q = shlex.quote(s.name)
        if os.path.dirname(s.name) and s.kind in ("file", "symlink", "fifo", "device", "dir", "sparse"):
            lines.append(f"mkdir -p {shlex.quote(os.path.dirname(s.name))}")
        if s.kind == "file":
            if len(s.data) < 100 and s.data.isascii():
                lines.append(f"printf %s {shlex.quote(s.data.decode())} > {q}")
            else:
                lines.append(f"cp {shlex.quote(os.path.join(case_dir, 'files', s.name))} {q}")
        elif s.kind == "dir":
            lines.append(f"mkdir -p {q}")
        elif s.kind == "symlink":
            lines.append(f"ln -s {shlex.quote(s.data.decode())} {q}")
        elif s.kind == "fifo":
            lines.append(f"mkfifo {q}")
        elif s.kind == "device":
            lines.append(f"mknod {q} c 1 3")
        elif s.kind == "sparse":
            lines.append(f"truncate -s {s.data.decode()} {q}")
        elif s.kind == "chmod000":
            lines.append(f"chmod 000 {q}")
        elif s.kind == "copy":
            lines.append(f"cp {shlex.quote(os.path.join(case_dir, 'files', 'map.h5'))} {q}   # the damaged map")
    return lines


def reproducer(outcome, case_dir, limits):
    """A shell script that reproduces the case by hand (files from case_dir)."""
    draft = outcome.case.draft
    lines = ["#!/bin/sh", f"# case {outcome.case.index} [{outcome.case.cls}] {outcome.case.base}: "
             + "; ".join(draft.notes)[:2000], 'cd "$(mktemp -d)" || exit', ]
    if SCENE in draft.args:
        lines.append(f"cp {shlex.quote(os.path.join(case_dir, 'files', SCENE))} {SCENE}")
    lines += [line for line in setup_shell([s for s in draft.setup if s.kind not in ("flip", "version")], case_dir)]
    cmd = " ".join(shlex.quote(a) for a in outcome.argv)
    if draft.signal:
        lines.append(f"{cmd} & pid=$!; sleep {draft.signal[1]}; kill -{draft.signal[0][3:]} $pid; wait $pid; echo exit $?")
    else:
        lines.append(f"timeout -s TERM {limits.timeout:.0f} {cmd}; echo exit $?")
    return "\n".join(lines) + "\n"


def command_line(outcome, limit=400):
    """The case's command line, shortened for the report."""
    text = " ".join(shlex.quote(a) for a in outcome.argv[1:])
    exe = os.path.basename(outcome.argv[0])
    text = f"{exe} {text}"
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def save_case(outcome, case_dir, limits, shared):
    """Writes the case's files and its reproducer under case_dir."""
    files = os.path.join(case_dir, "files")
    os.makedirs(files, exist_ok=True)
    draft = outcome.case.draft
    if SCENE in draft.args:
        with open(os.path.join(files, SCENE), "wb") as f:
            f.write(draft.scene)
    for s in draft.setup:
        if s.kind == "file" and not (len(s.data) < 100 and s.data.isascii()):
            os.makedirs(os.path.dirname(os.path.join(files, s.name)), exist_ok=True)
            with open(os.path.join(files, s.name), "wb") as f:
                f.write(s.data)
    if draft.post and shared.get("damage-map"):  # the damaged map again, as the case made it
        make_setup(files, [s for s in draft.setup if s.kind in ("copy", "flip", "version")], shared)
    with open(os.path.join(case_dir, "repro.sh"), "w") as f:
        f.write(reproducer(outcome, case_dir, limits))
    with open(os.path.join(case_dir, "result.txt"), "w") as f:
        res = outcome.result
        f.write(f"exit {res.rc} signal {res.signum} wall {res.wall:.2f} s peak RSS {res.maxrss_mb:.0f} MB\n")
        for tag, detail in outcome.problems:
            f.write(f"{tag}: {detail}\n")
        f.write("--- stdout (first 2000 bytes)\n" + res.stdout[:2000].decode(errors="replace"))
        f.write("\n--- stderr (first 2000 bytes)\n" + res.stderr[:2000].decode(errors="replace") + "\n")
