#!/usr/bin/env bash
# Runs every command of commands.txt with one vibromap binary and keeps its outputs, so that two
# binaries (before and after a restructuring) can be compared output by output (compare.py):
#
#   tests/benchmarks/reference_outputs/run.sh OLD/vibromap /tmp/before
#   tests/benchmarks/reference_outputs/run.sh build/vibromap /tmp/after
#   tests/benchmarks/reference_outputs/compare.py /tmp/before /tmp/after
#
# The commands run from the repository's root on its jobs/ scenes. Outputs name the paths they
# were written to, so every run writes into the same scratch folder (one run at a time: a lock),
# then moves it to OUTDIR. Each command leaves NAME.out (stdout), NAME.err and NAME.rc.
set -u
if [ $# -ne 2 ]; then
  echo "usage: $0 VIBROMAP OUTDIR" >&2
  exit 2
fi
VM=$(realpath "$1"); OUT=$2
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
SCRATCH=${TMPDIR:-/tmp}/vibromap-reference-outputs
exec 9>"$SCRATCH.lock"
flock 9
rm -rf "$SCRATCH"; mkdir -p "$SCRATCH"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cd "$ROOT"
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue;; esac
  name=$(echo "${line%%|*}" | xargs)
  cmd=${line#*|}
  cmd=${cmd//VM/$VM}; cmd=${cmd//D\//$SCRATCH/}
  start=$(date +%s%N)
  eval "$cmd" < /dev/null > "$SCRATCH/$name.out" 2> "$SCRATCH/$name.err"
  echo $? > "$SCRATCH/$name.rc"
  printf '%-20s rc=%s %6d ms\n' "$name" "$(cat "$SCRATCH/$name.rc")" $((($(date +%s%N) - start) / 1000000))
done < "$HERE/commands.txt"
rm -rf "$OUT"; mv "$SCRATCH" "$OUT"
