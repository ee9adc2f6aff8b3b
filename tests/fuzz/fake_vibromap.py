#!/usr/bin/env python3
"""A deliberately faulty stand-in for vibromap, for the fuzzer's self-test (fuzz_tests.cmake):
the fuzzer run on it must report each fault below, so a check that stopped working fails a test.

Faults of every command: writes its output through links, into FIFOs and devices, over an
existing file (canary, expected-exit); leaves FILE.lock behind (leak); prints Infinity in JSON
(nonfinite-json); a file it cannot write ends it with exit 1 and a two-line message (exit-1,
stderr). Of one command each: accuracy takes 200 MB (memory, with --memory-mb 100); continue
ignores SIGTERM and sleeps (hang); orbit-diagram aborts (crash); basins writes a file and exits
2 (wrote-on-exit-2); sweep exits 1 (exit-1).
"""
import os
import signal
import sys
import time

KEYS = """key  default  unit  allowed  meaning
system.m1  1000.0  kg  > 0  main body mass
system.omega1  6.283  rad/s  > 0  spring
contact.law  "hertz"  -  one of "hertz", "flores"  contact law
forcing.omega  7.23  rad/s  > 0  forcing frequency
solver.rk4_steps  16384  -  an integer >= 1  steps
analysis.max_periods  2000  -  an integer >= 1  budget
census.x1  (scaled)  m  [lo, hi], lo <= hi  box side
optimise.m2  (fixed)  kg  bounds > 0  free parameter { min, max[, scale] }
"""
HELP = "Options:\n  -o,--output FILE  -t,--trajectory FILE  --csv FILE  -f,--format  --overwrite  -p  --from\n"


def main(args):
    if not args or args[0] == "keys":
        print(KEYS * 4)
        return 0
    if "--help" in args:
        print(HELP)
        return 0
    command = args[0]
    if command == "accuracy":
        hog = b"x" * (200 << 20)  # written, so resident
        del hog
    elif command == "continue":
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        time.sleep(60)
    elif command == "orbit-diagram":
        os.abort()
    elif command == "basins":
        open("junk.h5", "w").close()
        print("vibromap: error: a refusal that wrote a file first", file=sys.stderr)
        return 2
    elif command == "sweep":
        print("vibromap: error: an internal error", file=sys.stderr)
        return 1
    if len(args) > 1 and not args[1].startswith("-"):
        try:
            with open(args[1], "rb") as f:
                f.read()
        except OSError:
            pass
    for opt in ("-o", "-t", "--csv"):
        if opt in args and args.index(opt) + 1 < len(args):
            out = args[args.index(opt) + 1]
            try:
                with open(out, "w") as f:
                    f.write("written\n")
                open(out + ".lock", "w").close()
            except OSError as exc:
                print(f"vibromap: error: {exc}\n  while writing", file=sys.stderr)
                return 1
    if "json" in args:
        print('{"k_con": Infinity}')
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
