#!/usr/bin/env python3
"""A seeded fuzzer of vibromap's command line (issue #28): mutated scenes, non-file scenes,
mutated options, hostile outputs, signals during a run, damaged maps, over every command.

Each case runs single-process (no mpirun: the campaign commands run as one MPI rank) in a
scratch directory of its own, bounded in time and memory, and must end with exit code 0, 2, 3
or 4, never 1 nor a signal; a failure prints one line 'vibromap: error: ...' and nothing on
stdout; exit 2 writes nothing; no link, node, FIFO or directory given as an output is written
through, replaced or removed; every number in the outputs is finite; nothing is left behind
(fuzz_run.py lists every check and its tag).

  tests/fuzz/fuzz_cli.py --exe build/vibromap                  # CI: seed 28, 150 cases
  VIBROMAP_FUZZ_CASES=3000 VIBROMAP_FUZZ_SEED=7 tests/fuzz/fuzz_cli.py --report long.txt
  tests/fuzz/fuzz_cli.py --classes output,scene-path          # only these classes
  tests/fuzz/fuzz_cli.py --seed 28 --classes options --case 17 --keep   # replay one case

Cases are numbered; case i of a class list and a seed is the same on every machine (the
binary's `keys` and `--help` output aside, which the fuzzer reads at start-up). The report
gives counts by exit code and by class, and each failing case with its command line and a
shell script that reproduces it (under --failures-dir). Exit status: 0 when every case
passed, 1 when some failed, 2 for a usage error.
"""
import argparse
import collections
import concurrent.futures
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import fuzz_cases  # noqa: E402
from fuzz_cases import CLASSES, Generator  # noqa: E402
from fuzz_run import (Limits, Outcome, RunResult, command_line, map_content, run_bounded, run_case,  # noqa: E402
                      save_case)

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def env_default(name, default, kind=str):
    value = os.environ.get(name)
    return kind(value) if value not in (None, "") else default


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("--exe", default=env_default("VIBROMAP_EXE", os.path.join(REPO, "build", "vibromap")),
                   help="the vibromap executable (env VIBROMAP_EXE; default build/vibromap)")
    p.add_argument("--seed", type=int, default=env_default("VIBROMAP_FUZZ_SEED", 28, int),
                   help="seed (env VIBROMAP_FUZZ_SEED; default 28)")
    p.add_argument("--cases", type=int, default=env_default("VIBROMAP_FUZZ_CASES", 150, int),
                   help="number of cases (env VIBROMAP_FUZZ_CASES; default 150)")
    p.add_argument("--classes", default=env_default("VIBROMAP_FUZZ_CLASSES", "all"),
                   help=f"comma-separated classes or 'all' (env VIBROMAP_FUZZ_CLASSES): {', '.join(CLASSES)}")
    p.add_argument("--case", type=int, action="append", default=[], help="run only case N (repeatable)")
    p.add_argument("--jobs", "-j", type=int, default=env_default("VIBROMAP_FUZZ_JOBS", 2, int),
                   help="cases run at once (default 2)")
    p.add_argument("--timeout", type=float, default=20.0, help="seconds a case may take (default 20)")
    p.add_argument("--memory-mb", type=float, default=500.0, help="peak memory of a case, MB (default 500)")
    p.add_argument("--signal-bound", type=float, default=3.0,
                   help="seconds from SIGTERM or SIGINT to the end of a run (default 3)")
    p.add_argument("--quick-bound", type=float, default=5.0,
                   help="seconds for a refusal the issue wants at once (default 5)")
    p.add_argument("--report", default=env_default("VIBROMAP_FUZZ_REPORT", ""),
                   help="write the full report here (env VIBROMAP_FUZZ_REPORT)")
    p.add_argument("--failures-dir", default="",
                   help="save each failing case's files and repro.sh here (default: beside --report)")
    p.add_argument("--workdir", default="", help="scratch directories go here (default: a new temporary directory)")
    p.add_argument("--keep", action="store_true", help="keep the scratch directories")
    p.add_argument("--list", action="store_true", help="print the cases, run nothing")
    p.add_argument("--minimise", action="store_true",
                   help="shrink each failing case: drop its mutations one at a time while the failure stays")
    p.add_argument("--quiet", "-q", action="store_true", help="no line per failing case while running")
    p.add_argument("--expect-tags", default="",
                   help="self-test: succeed only when every one of these comma-separated tags is reported "
                        "(the run on tests/fuzz/fake_vibromap.py)")
    args = p.parse_args(argv)
    args.classes = list(CLASSES) if args.classes == "all" else [c.strip() for c in args.classes.split(",") if c.strip()]
    unknown = [c for c in args.classes if c not in CLASSES]
    if unknown:
        p.error(f"unknown class {', '.join(unknown)} (allowed: {', '.join(CLASSES)}, all)")
    if not os.access(args.exe, os.X_OK):
        p.error(f"{args.exe}: not an executable (give --exe or VIBROMAP_EXE)")
    args.exe = os.path.abspath(args.exe)
    return args


def child_env(workdir):
    """The runs' environment: one MPI rank without mpirun and without its daemon (faster
    start, nothing left behind when a case is killed), Open MPI's files in the workdir."""
    env = dict(os.environ)
    env.update(OMPI_MCA_ess_singleton_isolated="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_btl="self,vader", TMPDIR=os.path.join(workdir, "tmp"),
               PYTHONDONTWRITEBYTECODE="1", MPLCONFIGDIR=os.path.join(workdir, "tmp"))
    env.pop("VIBROMAP_FUZZ_CASES", None)
    os.makedirs(env["TMPDIR"], exist_ok=True)
    return env


def probe_help(exe, env):
    """The options each command's --help lists: value options the binary lacks are dropped
    from the mutations, and flags (--overwrite) are used where the command has them."""
    def help_of(command):
        return subprocess.run([exe, command, "--help"], env=env, capture_output=True, text=True, timeout=60).stdout

    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        texts = dict(zip(fuzz_cases.ALL_COMMANDS, pool.map(help_of, fuzz_cases.ALL_COMMANDS)))
    flags = {}
    for command, out in texts.items():
        options = set(re.findall(r"(?:^|[\s,])(--?[A-Za-z][\w-]*)", out))
        flags[command] = options
        fuzz_cases.VALUE_OPTIONS[command] = tuple(o for o in fuzz_cases.VALUE_OPTIONS[command] if o in options)
    return flags


def probe_keys(exe, env):
    out = subprocess.run([exe, "keys"], env=env, capture_output=True, text=True, timeout=30).stdout
    keys = fuzz_cases.parse_keys(out)
    return keys if len(keys) > 20 else fuzz_cases.FALLBACK_KEYS


def can_mknod(workdir):
    path = os.path.join(workdir, "probe-node")
    try:
        os.mknod(path, 0o666 | 0o020000, os.makedev(1, 3))
        os.unlink(path)
        return True
    except OSError:
        return False


def attribute_regions(path):
    """Byte ranges of the file holding its root attributes' text (title, Conventions, scene,
    identity, ...): where the damage class flips bits most of the time."""
    import h5py
    with open(path, "rb") as f:
        data = f.read()
    regions = []
    with h5py.File(path, "r") as h:
        for value in h.attrs.values():
            if isinstance(value, bytes):
                value = value.decode(errors="replace")
            if isinstance(value, str) and value:
                at = data.find(value.encode())
                if at >= 0:
                    regions.append((at, at + len(value.encode())))
    return regions


def make_damage_map(exe, env, workdir, scenes, limits):
    """The intact map the damage class damages: the shrunk demo E1 x E2 sweep (4 cells)."""
    d = os.path.join(workdir, "damage-base")
    os.makedirs(d)
    with open(os.path.join(d, fuzz_cases.SCENE), "wb") as f:
        f.write(scenes["e1_e2"])
    res = run_bounded([exe, "sweep", fuzz_cases.SCENE, "-o", "map.h5", "-q"], d, env, limits)
    path = os.path.join(d, "map.h5")
    if res.rc != 0 or not os.path.exists(path):
        return None
    return (path, attribute_regions(path), map_content(path))


def safe_run(case, exe, env, limits, workdir, shared, keep):
    """run_case, with an error of the fuzzer itself reported as the case's problem."""
    try:
        return run_case(case, exe, REPO, env, limits, workdir, shared, keep)
    except Exception as exc:  # a bug here must not hide the other cases' results
        import traceback
        return Outcome(case=case, argv=[exe] + case.draft.args, result=RunResult(),
                       problems=[("fuzzer-error", f"{type(exc).__name__}: {exc} "
                                  f"{traceback.format_exc().splitlines()[-3].strip()}")])


def minimise(outcome, gen, exe, env, limits, workdir, shared):
    """Drops mutations one at a time while the case still fails with its first tag."""
    case = outcome.case
    tag = outcome.problems[0][0]
    mutations = list(case.mutations)
    best = outcome
    i = 0
    while i < len(mutations) and len(mutations) > 1:
        trial = mutations[:i] + mutations[i + 1:]
        smaller = gen.build(case.index, case.cls, case.base, trial)
        result = run_case(smaller, exe, REPO, env, limits, workdir, shared)
        if any(t == tag for t, _ in result.problems):
            mutations, best = trial, result
        else:
            i += 1
    return best


def exit_label(res):
    if res.timed_out:
        return "timeout"
    if res.mem_killed:
        return "memory-killed"
    if res.rc is None:
        return f"signal {res.signum}"
    return f"exit {res.rc}"


def summary(outcomes, args, elapsed):
    """The report: counts by exit code and class, then the failures grouped by tag."""
    lines = [f"vibromap fuzz: seed {args.seed}, {len(outcomes)} cases, classes {','.join(args.classes)}, "
             f"{args.jobs} jobs, {elapsed:.1f} s, exe {args.exe}"]
    by_exit = collections.Counter(exit_label(o.result) for o in outcomes)
    lines.append("by exit: " + ", ".join(f"{k}: {v}" for k, v in sorted(by_exit.items())))
    by_class = collections.defaultdict(lambda: [0, 0])
    for o in outcomes:
        by_class[o.case.cls][0] += 1
        by_class[o.case.cls][1] += bool(o.problems)
    lines.append("by class (cases, failing): " + ", ".join(f"{c} {n} {f}" for c, (n, f) in by_class.items()))
    worst = max(outcomes, key=lambda o: o.result.wall, default=None)
    rss = max(outcomes, key=lambda o: o.result.maxrss_mb, default=None)
    if worst:
        lines.append(f"slowest case {worst.case.index}: {worst.result.wall:.1f} s; "
                     f"largest peak RSS case {rss.case.index}: {rss.result.maxrss_mb:.0f} MB")
    failing = [o for o in outcomes if o.problems]
    by_tag = collections.defaultdict(list)
    for o in failing:
        for tag in dict.fromkeys(t for t, _ in o.problems):
            by_tag[tag].append(o)
    lines.append(f"failing cases: {len(failing)}" + (" (by tag: " + ", ".join(
        f"{t} {len(v)}" for t, v in sorted(by_tag.items(), key=lambda kv: -len(kv[1]))) + ")" if failing else ""))
    return lines, by_tag


def failure_lines(by_tag, args, limit=None):
    lines = []
    for tag, cases in sorted(by_tag.items(), key=lambda kv: -len(kv[1])):
        commands = collections.Counter(o.case.draft.command for o in cases)
        lines.append(f"== {tag}: {len(cases)} cases ({', '.join(f'{c} {n}' for c, n in commands.most_common())})")
        # The simplest first: fewest mutations, then the shortest command line.
        cases = sorted(cases, key=lambda o: (len(o.case.draft.notes), len(command_line(o, 10**6)), o.case.index))
        for o in cases[:limit]:
            detail = next(d for t, d in o.problems if t == tag)
            lines.append(f"  case {o.case.index} [{o.case.cls}] {exit_label(o.result)} {o.result.wall:.1f} s: {detail}")
            lines.append(f"    {command_line(o)}")
            if o.case.draft.notes:
                lines.append(f"    mutations: {'; '.join(o.case.draft.notes)[:300]}")
        if limit is not None and len(cases) > limit:
            lines.append(f"  ... {len(cases) - limit} more")
    lines.append(f"replay one: {sys.argv[0]} --exe {args.exe} --seed {args.seed} "
                 f"--classes {','.join(args.classes)} --case N")
    return lines


def main(argv=None):
    args = parse_args(argv)
    workdir = args.workdir or tempfile.mkdtemp(prefix="vibromap-fuzz-")
    os.makedirs(workdir, exist_ok=True)
    try:
        return fuzz(args, workdir)
    finally:
        if not args.keep and not args.workdir:
            shutil.rmtree(workdir, ignore_errors=True)


def default_signals():
    """SIGINT and SIGTERM as a terminal gives them to the runs: a shell starts a background job
    (`fuzz_cli.py &`, nohup) with SIGINT ignored, and a run inherits an ignored signal."""
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if signal.getsignal(signal.SIGTERM) == signal.SIG_IGN:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def fuzz(args, workdir):
    default_signals()
    env = child_env(workdir)
    limits = Limits(args.timeout, args.memory_mb, args.signal_bound, args.quick_bound)
    scenes = fuzz_cases.load_scenes(os.path.join(REPO, "jobs"))
    flags = probe_help(args.exe, env)
    gen = Generator(args.seed, args.classes, scenes, probe_keys(args.exe, env), flags, can_mknod(workdir),
                    fuzz_cases.name_max(workdir), os.path.join(REPO, "jobs"))
    indices = args.case or list(range(args.cases))
    cases = [gen.case(i) for i in indices]
    if args.list:
        for c in cases:
            print(f"{c.index} [{c.cls}] {c.base}: {' '.join(c.draft.args)[:200]} | {'; '.join(c.draft.notes)[:200]}")
        return 0
    shared = {}
    if "damage" in args.classes:
        damage = make_damage_map(args.exe, env, workdir, scenes, limits)
        shared["damage-map"] = damage or ("/nonexistent", [], None)
    start = time.monotonic()
    outcomes = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [pool.submit(safe_run, c, args.exe, env, limits, workdir, shared, args.keep) for c in cases]
        for fut in concurrent.futures.as_completed(futures):
            o = fut.result()
            outcomes.append(o)
            if o.problems and not args.quiet:
                print(f"FAIL case {o.case.index} [{o.case.cls}] {exit_label(o.result)}: "
                      f"{', '.join(dict.fromkeys(t for t, _ in o.problems))}: {command_line(o, 200)}", flush=True)
    outcomes.sort(key=lambda o: o.case.index)
    if args.minimise:
        outcomes = [minimise(o, gen, args.exe, env, limits, workdir, shared) if o.problems and len(o.case.mutations) > 1
                    else o for o in outcomes]
    elapsed = time.monotonic() - start
    head, by_tag = summary(outcomes, args, elapsed)
    print("\n".join(head))
    if by_tag:
        print("\n".join(failure_lines(by_tag, args, limit=3)))
    failures_dir = args.failures_dir or (os.path.splitext(args.report)[0] + "_cases" if args.report else "")
    if args.report:
        with open(args.report, "w") as f:
            f.write("\n".join(head + failure_lines(by_tag, args)) + "\n")
        print(f"report: {args.report}")
    if failures_dir and by_tag:
        shutil.rmtree(failures_dir, ignore_errors=True)
        for o in outcomes:
            if o.problems:
                save_case(o, os.path.join(failures_dir, f"case-{o.case.index:05d}"), limits, shared)
        print(f"failing cases' files and repro.sh: {failures_dir}")
    if args.expect_tags:
        missing = [tag for tag in args.expect_tags.split(",") if tag not in by_tag]
        print(f"self-test: {'every expected tag reported' if not missing else 'not reported: ' + ', '.join(missing)}")
        return 1 if missing else 0
    return 1 if by_tag else 0


if __name__ == "__main__":
    sys.exit(main())
