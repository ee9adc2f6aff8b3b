#!/usr/bin/env bash
# compare.sh: times whole commands from outside, start-up included, the way the figures of
# docs/benchmarks.md were measured. With one command: a warm-up run, then N timed runs; prints
# the median, min and max. With two: A and B in turn (A B A B ..., each after a warm-up of both),
# so that a drift of the machine's speed hits both alike; prints each one's median, min and max
# and the ratio A/B (the median of the N pair ratios, and the ratio of the medians).
#
#   tests/benchmarks/compare.sh [-n N] [-w W] 'COMMAND A' ['COMMAND B']
#     -n N   timed runs of each command (default 3)
#     -w W   warm-up runs of each command before them (default 1; 0 for none)
#   e.g. tests/benchmarks/compare.sh -n 3 \
#          'build/vibromap continue jobs/paper/table2.toml --param omega --from 3 --to 12 --pd-depth 0'
#
# Each command runs with bash -c in the current directory, its output discarded. Exit status:
# 0; 1 when a command fails (its exit status and last lines of stderr named); 2 for a usage error.
# Needs bash 5 (EPOCHREALTIME) and awk.
set -uo pipefail

runs=3
warmups=1
usage() { echo "usage: tests/benchmarks/compare.sh [-n N] [-w W] 'COMMAND A' ['COMMAND B']" >&2; exit 2; }
while getopts "n:w:h" opt; do
  case "$opt" in
    n) runs="$OPTARG" ;;
    w) warmups="$OPTARG" ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
[ $# -eq 1 ] || [ $# -eq 2 ] || usage
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "compare.sh: error: -n $runs: expected an integer >= 1" >&2; exit 2; }
[[ "$warmups" =~ ^[0-9]+$ ]] || { echo "compare.sh: error: -w $warmups: expected an integer >= 0" >&2; exit 2; }
[ -n "${EPOCHREALTIME:-}" ] || { echo "compare.sh: error: needs bash 5 (EPOCHREALTIME)" >&2; exit 2; }
commands=("$@")
names=(A B)
err="$(mktemp)"
trap 'rm -f "$err"' EXIT

# Runs command $1 once; prints its wall time in seconds; exits 1 when it fails.
time_one() {
  local start end status
  start=$EPOCHREALTIME
  bash -c "$1" >/dev/null 2>"$err"
  status=$?
  end=$EPOCHREALTIME
  if [ $status -ne 0 ]; then
    echo "compare.sh: error: command $2 exited with status $status: $1" >&2
    tail -n 3 "$err" | sed 's/^/  /' >&2
    exit 1
  fi
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.6f\n", b - a }'
}

# median, min and max of the numbers on stdin, as "median min max".
stats() {
  sort -g | awk '{ v[NR] = $1 } END { m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
                                      printf "%.4g %.4g %.4g\n", m, v[1], v[NR] }'
}

for i in "${!commands[@]}"; do
  echo "${names[$i]}: ${commands[$i]}"
done
for ((w = 0; w < warmups; w++)); do
  for i in "${!commands[@]}"; do time_one "${commands[$i]}" "${names[$i]}" >/dev/null || exit 1; done
done
times_a=() times_b=() ratios=()
for ((r = 0; r < runs; r++)); do
  ta="$(time_one "${commands[0]}" A)" || exit 1
  times_a+=("$ta")
  if [ ${#commands[@]} -eq 2 ]; then
    tb="$(time_one "${commands[1]}" B)" || exit 1
    times_b+=("$tb")
    ratios+=("$(awk -v a="$ta" -v b="$tb" 'BEGIN { printf "%.6f\n", a / b }')")
  fi
done
order="each"
[ ${#commands[@]} -eq 2 ] && order="each, in turn A B"
echo "runs: $runs $order (after $warmups warm-up run(s) of each)"
read -r ma mina maxa < <(printf '%s\n' "${times_a[@]}" | stats)
echo "A: median $ma s (min $mina, max $maxa)"
if [ ${#commands[@]} -eq 2 ]; then
  read -r mb minb maxb < <(printf '%s\n' "${times_b[@]}" | stats)
  echo "B: median $mb s (min $minb, max $maxb)"
  read -r mr minr maxr < <(printf '%s\n' "${ratios[@]}" | stats)
  ofmedians="$(awk -v a="$ma" -v b="$mb" 'BEGIN { printf "%.4g\n", a / b }')"
  echo "A/B: $mr (median of the $runs pair ratios, min $minr, max $maxr; ratio of the medians $ofmedians)"
fi
