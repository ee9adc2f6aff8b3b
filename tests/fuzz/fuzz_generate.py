#!/usr/bin/env python3
"""Builds the command-line fuzzer's cases (fuzz_cases.py) for many seeds without running
vibromap: every case of every seed must build, so that no seed makes the fuzzer itself fail
before it has tested anything.

  tests/fuzz/fuzz_generate.py --seeds 1-1000 --cases 150     # the ctest fuzz.generate

The key catalogue is read from docs/keys.md (what `vibromap keys` prints, kept equal to it by
the test docs.keys_md) and every command is taken to have every option the fuzzer knows, so
the mutations that depend on them are built too. Exit status: 0 when every case was built, 1
when some raised (each listed with its seed and index), 2 for a usage error.
"""
import argparse
import concurrent.futures
import os
import re
import sys
import time
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import fuzz_cases  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def keys_from_markdown(path):
    """The keys of docs/keys.md's tables, as `vibromap keys` lines (key, then its columns)."""
    lines = []
    with open(path, encoding="utf-8") as f:
        for row in f:
            m = re.match(r"^\|\s*`([a-z]+\.[A-Za-z0-9_]+)`\s*\|(.*)$", row)
            if m:
                lines.append(m.group(1) + "  " + m.group(2).replace("|", "  ").replace("`", ""))
    return fuzz_cases.parse_keys("\n".join(lines))


def all_flags():
    """Every command with every option the fuzzer knows (and --overwrite): the most mutations."""
    return {c: set(fuzz_cases.VALUE_OPTIONS[c]) | {"--overwrite"} for c in fuzz_cases.ALL_COMMANDS}


def seed_range(text):
    lo, _, hi = text.partition("-")
    return range(int(lo), int(hi or lo) + 1)


def build_seeds(seeds, cases):
    """Builds `cases` cases of each seed; returns (cases built, one line per case that raised)."""
    keys = keys_from_markdown(os.path.join(REPO, "docs", "keys.md"))
    scenes = fuzz_cases.load_scenes(os.path.join(REPO, "jobs"))
    flags = all_flags()
    failures, built = [], 0
    for seed in seeds:
        gen = fuzz_cases.Generator(seed, list(fuzz_cases.CLASSES), scenes, keys, flags, True, 255,
                                   os.path.join(REPO, "jobs"))
        for index in range(cases):
            try:
                gen.case(index)
                built += 1
            except Exception as exc:  # the fuzzer's own bug: reported with its seed and case
                where = traceback.extract_tb(exc.__traceback__)[-1]
                failures.append(f"seed {seed} case {index}: {type(exc).__name__}: {exc} "
                                f"({os.path.basename(where.filename)}:{where.lineno} in {where.name})")
    return built, failures


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--seeds", default="1-1000", help="seeds LO-HI (default 1-1000)")
    p.add_argument("--cases", type=int, default=150, help="cases per seed (default 150, the fuzzer's)")
    p.add_argument("--jobs", "-j", type=int, default=2, help="processes (default 2)")
    args = p.parse_args(argv)
    if len(keys_from_markdown(os.path.join(REPO, "docs", "keys.md"))) < 20:
        print("fuzz_generate: error: docs/keys.md lists fewer than 20 keys", file=sys.stderr)
        return 2
    seeds = list(seed_range(args.seeds))
    start = time.monotonic()
    shares = [seeds[i::max(1, args.jobs)] for i in range(max(1, args.jobs))]
    with concurrent.futures.ProcessPoolExecutor(max_workers=len(shares)) as pool:
        results = list(pool.map(build_seeds, shares, [args.cases] * len(shares)))
    built = sum(r[0] for r in results)
    failures = [line for r in results for line in r[1]]
    print(f"fuzz_generate: seeds {args.seeds}, {built} cases built, {len(failures)} raised, "
          f"{time.monotonic() - start:.1f} s")
    for line in failures[:20]:
        print("  " + line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
