#!/usr/bin/env bash
# The README's main job over the E1 x E2 plane of jobs/demo/e1_e2.toml, on the local cores: one
# map, the scene's 23 x 22 grid sharpened 8x per axis where the answer to "is the motion soft?"
# changes (177 x 169 points, refined 3 levels where soft or hertz_valid changes: about 8 % of
# them solved, the rest inherited from the nearest solved point and audited), the soft region's
# edges as curves (k_con = 10 and z_max/R* = 0.05 of the (1,1) orbit, continued in (E2, E1) to
# the solver's tolerance), and three pictures of the map: regimes, k_con and where the motion is
# soft, the last two with the edges drawn on them.
# Usage: jobs/demo/run.sh [OUTDIR] [RANKS]
#   OUTDIR  where the map and the PNGs go (default: demo-out)
#   RANKS   MPI ranks (default: the number of cores)
# Ctrl-C (or SIGTERM) stops the sweep after a final checkpoint (exit 3); running the script
# again resumes the map.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
top="$(cd "$here/../.." && pwd)"
out="${1:-demo-out}"
ranks="${2:-$(nproc)}"
exe="${VIBROMAP_EXE:-$top/build/vibromap}"
mkdir -p "$out" || exit 4

# Open MPI on one node, started in a fraction of a second wherever it runs: shared memory only
# (the TCP transport's start-up grows with the number of network interfaces: 13-22 s with 300,
# as on a container host), and no hwloc GL probe (it tries X displays :0-:9 and can hang on a
# port 6000-6009 held by something else). A value already in the environment wins.
export OMPI_MCA_pml="${OMPI_MCA_pml:-ob1}"
export OMPI_MCA_btl="${OMPI_MCA_btl:-self,vader}"
export HWLOC_COMPONENTS="${HWLOC_COMPONENTS:--gl,-opencl}"

# Root may run mpirun only when it says so (a container or CI machine); more ranks than
# cores need oversubscription.
mpi_flags=(-n "$ranks")
[ "$(id -u)" -eq 0 ] && mpi_flags+=(--allow-run-as-root)
[ "$ranks" -gt "$(nproc)" ] && mpi_flags+=(--oversubscribe)

# sweep MAP [--set KEY=VALUE ...]: the demo scene into MAP, resumed when MAP is there.
# mpirun turns SIGINT and SIGTERM into SIGTERM for the ranks a second later and SIGKILL a second
# after that, and exits 1; it forwards SIGUSR1 and returns the ranks' exit code. So mpirun runs
# in a session of its own (Ctrl-C reaches this script only), and Ctrl-C, SIGTERM or SIGHUP is passed on
# as SIGUSR1: the sweep checkpoints and every rank exits 3.
sweep() {
  local map="$1"
  shift
  local args=(sweep "$here/e1_e2.toml" -o "$map" "$@")
  [ -f "$map" ] && args+=(--resume)   # continue an interrupted run; a finished map is left as it is
  local pid="" status=0
  trap '[ -n "$pid" ] && kill -s USR1 "$pid" 2>/dev/null' INT TERM HUP
  setsid mpirun "${mpi_flags[@]}" "$exe" "${args[@]}" &
  pid=$!
  while :; do
    wait "$pid"
    status=$?
    if [ "$status" -le 128 ] || ! kill -0 "$pid" 2>/dev/null; then break; fi
  done
  trap - INT TERM HUP
  if [ "$status" -ne 0 ]; then
    [ "$status" -eq 3 ] && echo "demo: stopped with a checkpoint in $map; run jobs/demo/run.sh again to go on" >&2
    exit "$status"
  fi
}

map="$out/e1_e2.h5"
# The audit solves 0.3 % of the inherited points (78), drawn from the whole plane: its upper right
# (non-periodic and unresolved cells) is the costly part, and the default 1 % would add half the
# sweep's time; the map and its pictures state the audit's count and bound.
sweep "$map" --set sweep.refine=3 --set 'sweep.refine_on=["soft", "hertz_valid"]' --set sweep.refine_audit=0.003

edges="$out/soft_edges.h5"
"$exe" continue "$here/e1_e2.toml" --param contact.E2 --from 2e4 --to 2.1e11 --curve level:k_con=10 \
  --curve level:z_ratio=0.05 --param2 contact.E1 --from2 2e4 --to2 2.1e11 -o "$edges" --overwrite > /dev/null || exit $?

# The three pictures at once (each is mostly one Python start and one PNG); the first failure's
# status is the script's.
pids=()
"$top/postprocess/vibromap-post" plot_regime_map "$map" --x E1 --y E2 -o "$out/e1_e2_regimes.png" & pids+=($!)
"$top/postprocess/vibromap-post" plot_kcon_map "$map" --x E1 --y E2 --curves "$edges" -o "$out/e1_e2_kcon.png" & pids+=($!)
"$top/postprocess/vibromap-post" plot_soft_map "$map" --x E1 --y E2 --curves "$edges" -o "$out/e1_e2_soft.png" & pids+=($!)
status=0
for pid in "${pids[@]}"; do
  wait "$pid" || { [ "$status" -eq 0 ] && status=$?; }
done
[ "$status" -eq 0 ] || exit "$status"
echo "demo: map $map, soft-region edges $edges, pictures $out/e1_e2_regimes.png $out/e1_e2_kcon.png $out/e1_e2_soft.png"
