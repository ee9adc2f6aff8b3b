#!/bin/bash
# End-to-end test of jobs/cluster/sweep.slurm on a real one-node Slurm on this machine.
#
#   tests/cluster/local_slurm.sh [VIBROMAP_EXE]      as root; builds nothing (default build/vibromap)
#
# It installs Debian's slurm-wlm, munge and python3-h5py when they are missing, writes a
# throwaway Slurm configuration in a temporary folder (nothing under /etc is touched), starts
# munged, slurmctld and slurmd directly (no systemd) on 127.0.0.1, and submits sweep.slurm with
# a 2-minute time limit and SIGUSR1 60 s before it, on a scene that takes about 2.5 minutes on
# 2 ranks. It checks that the job was signalled, that the map then held a checkpoint (some but
# not all cells done), that the job was requeued and resumed, that it ended COMPLETED, and that
# the final map equals a direct mpirun run of the same scene in every dataset but wall_s.
# The daemons are stopped and the folder removed at the end, whatever happens.
#
# Environment:
#   LOCAL_SLURM_LAUNCHERS  launchers to test, among auto srun mpirun (default: auto)
#   LOCAL_SLURM_TIME       job time limit in minutes (default 2; Slurm's minimum is 1)
#   LOCAL_SLURM_LEAD       seconds before the limit for SIGUSR1 (default 60)
#   LOCAL_SLURM_GRID       cells per axis of the 2-D test scene (default 60: 3600 cells)
#   LOCAL_SLURM_PORT       slurmctld port; slurmd uses the next one (default 16817)
#   LOCAL_SLURM_KEEP=1     keep the temporary folder (logs, maps) after the run
# Exit code 0 when every check passed, 1 when one failed, 2 when it could not run.
set -u -o pipefail

t_start=$(date +%s)
top=$(cd "$(dirname "$0")/../.." && pwd)
script="$top/jobs/cluster/sweep.slurm"
exe=${1:-${VIBROMAP_EXE:-$top/build/vibromap}}
case "$exe" in /*) ;; *) exe="$(pwd)/$exe" ;; esac
launchers=${LOCAL_SLURM_LAUNCHERS:-auto}
time_limit=${LOCAL_SLURM_TIME:-2}
lead=${LOCAL_SLURM_LEAD:-60}
grid=${LOCAL_SLURM_GRID:-60}
port=${LOCAL_SLURM_PORT:-16817}
py=/usr/bin/python3

log() { printf 'local_slurm: %s %s\n' "$(date '+%H:%M:%S')" "$*"; }
die() { printf 'local_slurm: error: %s\n' "$*" >&2; exit 2; }
elapsed() { echo $(( $(date +%s) - t_start )); }

[ "$(id -u)" -eq 0 ] || die "run as root: it starts munged, slurmctld and slurmd"
[ -x "$exe" ] || die "no executable '$exe' (build it, or pass its path)"
[ -f "$script" ] || die "no $script"

# --- packages ----------------------------------------------------------------------------
missing=""
for p in slurm-wlm munge python3-h5py python3-numpy openmpi-bin; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  log "installing$missing"
  export DEBIAN_FRONTEND=noninteractive
  # shellcheck disable=SC2086
  { apt-get update -qq && apt-get install -y -qq --no-install-recommends $missing >/dev/null; } ||
    die "apt-get install$missing failed"
fi
# Debian's mpi/pmix plugin loads libpmix.so, which only libpmix-dev ships (libopenmpi-dev
# pulls it in); without it srun --mpi=pmix fails and sweep.slurm's auto mode uses mpirun.
for d in munged slurmctld slurmd sbatch scontrol mpirun; do
  command -v "$d" >/dev/null 2>&1 || die "$d not found after installing"
done

# --- throwaway configuration -------------------------------------------------------------
tmp=$(mktemp -d /tmp/vibromap-slurm.XXXXXX) || die "mktemp failed"
chmod 755 "$tmp"
mkdir -p "$tmp/etc" "$tmp/state" "$tmp/spool" "$tmp/log" "$tmp/run" "$tmp/munge" "$tmp/key" "$tmp/work"
chmod 700 "$tmp/key"
export SLURM_CONF="$tmp/etc/slurm.conf"
status=1

# shellcheck disable=SC2317  # run by the EXIT trap
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  if [ "$status" -ne 0 ] && [ "$rc" -eq 0 ]; then rc=1; fi
  if [ -f "$tmp/run/slurmctld.pid" ] && [ -n "$(squeue -h -o %i 2>/dev/null)" ]; then
    log "cancelling the jobs still queued or running"
    scancel --quiet --user=root 2>/dev/null
    for _ in $(seq 1 60); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 1; done
  fi
  local f pid
  for f in slurmd slurmctld munged; do
    [ -f "$tmp/run/$f.pid" ] || continue
    pid=$(cat "$tmp/run/$f.pid" 2>/dev/null) || continue
    [ -n "$pid" ] || continue
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 1 20); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.5
    done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null
  done
  if [ "${LOCAL_SLURM_KEEP:-0}" = 1 ]; then
    log "kept $tmp"
  else
    rm -rf "$tmp"
  fi
  log "daemons stopped; took $(elapsed) s; exit $rc"
  exit "$rc"
}
trap cleanup EXIT
trap 'log "interrupted"; exit 2' INT TERM

# munge: our own key, socket, pid, log and seed files (--force: no checks of /etc or /var).
dd if=/dev/urandom of="$tmp/key/munge.key" bs=1024 count=1 status=none
chmod 400 "$tmp/key/munge.key"
munged --force --socket="$tmp/munge/munge.sock" --key-file="$tmp/key/munge.key" \
  --pid-file="$tmp/run/munged.pid" --log-file="$tmp/log/munged.log" --seed-file="$tmp/run/munged.seed" ||
  die "munged did not start: $(tail -n 3 "$tmp/log/munged.log" 2>/dev/null)"

host=$(hostname -s)
# The node line as slurmd sees this machine (CPUs, sockets, cores, threads, memory).
node=$(slurmd -C 2>/dev/null | head -n 1)
case "$node" in NodeName=*) ;; *) die "slurmd -C gave no node line: $node" ;; esac
cpus=$(printf '%s\n' "$node" | sed -n 's/.* CPUs=\([0-9]*\).*/\1/p')
[ "${cpus:-0}" -ge 2 ] || die "the test needs 2 CPUs, slurmd -C says ${cpus:-?}"
: > "$tmp/etc/plugstack.conf"
cat > "$SLURM_CONF" <<EOF
# Throwaway one-node Slurm for tests/cluster/local_slurm.sh
ClusterName=vibromaptest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
# cred_expire is also how long a requeued job waits before it may start again (default 120 s).
AuthInfo=socket=$tmp/munge/munge.sock,cred_expire=10
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool/%n
SlurmctldPidFile=$tmp/run/slurmctld.pid
SlurmdPidFile=$tmp/run/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
PlugStackConfig=$tmp/etc/plugstack.conf
MailProg=/bin/true
# No cgroups needed: processes are tracked by parentage (pgid would miss Open MPI's ranks,
# each in a process group of its own).
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobRequeue=1
MinJobAge=3600
ReturnToService=2
SchedulerParameters=sched_interval=5
MpiDefault=none
# No slurmdbd: sacct -c reads this job completion log instead.
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$tmp/log/jobcomp.txt
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -f "$SLURM_CONF" || die "slurmctld did not start: $(tail -n 5 "$tmp/log/slurmctld.log" 2>/dev/null)"
slurmd -f "$SLURM_CONF" || die "slurmd did not start: $(tail -n 5 "$tmp/log/slurmd.log" 2>/dev/null)"
for _ in $(seq 1 60); do
  [ "$(sinfo -h -n "$host" -o %T 2>/dev/null)" = idle ] && break
  sleep 0.5
done
[ "$(sinfo -h -n "$host" -o %T 2>/dev/null)" = idle ] ||
  die "node $host is not idle: $(sinfo -h -N -o '%N %T %E' 2>&1); $(tail -n 5 "$tmp/log/slurmctld.log")"
log "Slurm $(sinfo -V | cut -d' ' -f2) up on $host ($cpus CPUs) in $tmp; $(mpirun --version | head -n 1)"
log "srun --mpi=list: $(srun --mpi=list 2>&1 | tr -s '\n\t ' ' ')"

# --- the scene: Table 2's system over E1 x E2, brute-force integration -------------------
scene="$tmp/work/scene.toml"
cat > "$scene" <<EOF
# local_slurm.sh: about 2.5 minutes on 2 ranks, checkpointed every 10 s
[system]
m2 = 310.0
omega2 = 3.606

[solver]
method = "dopri5"

[analysis]
steady = "integrate"

[sweep]
E1 = { from = 2e4, to = 2.1e11, n = $grid, scale = "log" }
E2 = { from = 2e4, to = 2.1e11, n = $grid, scale = "log" }
store = ["T_con", "k_con", "F_max", "z_max", "periods"]
checkpoint_interval = 10.0
progress_interval = 10.0
EOF
cells=$((grid * grid))

done_cells() {  # MAP -> "done total", or "- -" when the map does not open
  HDF5_USE_FILE_LOCKING=FALSE "$py" - "$1" <<'EOF' 2>/dev/null || echo "- -"
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    d = f["done"][()]
    print(int((d != 0).sum()), d.size)
EOF
}

job_field() {  # JOBID FIELD -> value from scontrol show job
  scontrol -o show job "$1" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1
}

failures=0
check() {  # CONDITION-STATUS MESSAGE
  if [ "$1" -eq 0 ]; then log "ok   $2"; else log "FAIL $2"; failures=$((failures + 1)); fi
}

# --- one Slurm run of sweep.slurm per launcher ---------------------------------------------
maps=""
for launcher in $launchers; do
  map="$tmp/work/map-$launcher.h5"
  joblog="$tmp/work/job-$launcher.log"
  log "[$launcher] sbatch --ntasks=2 --time=$time_limit --signal=B:USR1@$lead sweep.slurm ($cells cells)"
  jid=$(cd "$tmp/work" && VIBROMAP_SCENE="$scene" VIBROMAP_MAP="$map" VIBROMAP_EXE="$exe" \
        VIBROMAP_LAUNCHER="$launcher" sbatch --parsable --ntasks=2 --time="$time_limit" \
        --signal="B:USR1@$lead" --output="$joblog" --job-name="vibromap-$launcher" "$script") ||
    die "sbatch failed"
  jid=${jid%%;*}
  t_job=$(date +%s)
  last="" restarts_seen=0 partial=0 snapshots="" final=""
  while :; do
    state=$(job_field "$jid" JobState)
    restarts=$(job_field "$jid" Restarts)
    if [ "$state/$restarts" != "$last" ]; then
      log "[$launcher] job $jid $state (restarts ${restarts:-?}) at +$(( $(date +%s) - t_job )) s"
      last="$state/$restarts"
    fi
    # Between two runs of a requeued job no one writes the map: look at its checkpoint.
    if [ "${restarts:-0}" -gt "$restarts_seen" ] && [ "$state" = PENDING ]; then
      restarts_seen=$restarts
      read -r d n <<< "$(done_cells "$map")"
      snapshots="$snapshots $d/$n"
      log "[$launcher] requeued: the map holds $d of $n cells"
      if [ "$d" != - ] && [ "$d" -gt 0 ] && [ "$d" -lt "$n" ]; then partial=1; fi
    fi
    case "$state" in
      COMPLETED|FAILED|TIMEOUT|CANCELLED|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED|"")
        final=$state; break ;;
    esac
    if [ $(( $(date +%s) - t_job )) -gt 1800 ]; then
      log "[$launcher] job $jid still $state after 30 minutes: giving up"; final=$state; break
    fi
    sleep 1
  done
  exitcode=$(job_field "$jid" ExitCode)
  log "[$launcher] job $jid ended $final, exit code $exitcode, restarts $(job_field "$jid" Restarts), $(( $(date +%s) - t_job )) s"
  log "[$launcher] job log:"
  sed 's/^/    | /' "$joblog" | grep -v -E '^    \| (sweep: |-+$|\s*$)' | head -n 80

  grep -q "batch shell received SIGUSR1" "$joblog"
  check $? "[$launcher] the batch shell got SIGUSR1 before the time limit and passed it on"
  grep -q "sweep stopped by SIGUSR1" "$joblog"
  check $? "[$launcher] the sweep stopped with exit code 3 and the script named the signal"
  [ "$partial" -eq 1 ]
  check $? "[$launcher] after a stop the map held a checkpoint with some but not all cells (done/total:${snapshots:- none})"
  [ "$(job_field "$jid" Restarts)" -ge 1 ] 2>/dev/null && grep -q "requeued job $jid" "$joblog"
  check $? "[$launcher] the job requeued itself ($(job_field "$jid" Restarts) restarts)"
  grep -q -- "--resume" "$joblog" && grep -q "restart [1-9]" "$joblog"
  check $? "[$launcher] a later run resumed the map (--resume)"
  [ "$final" = COMPLETED ] && [ "$exitcode" = 0:0 ]
  check $? "[$launcher] the job ended COMPLETED with exit code 0:0 (scontrol: $final $exitcode)"
  comp=$(sacct -c -n -P -o jobid,state,exitcode 2>/dev/null | awk -F'|' -v j="$jid" '$1 == j' | tail -n 1)
  [ "${comp#*|}" = "COMPLETED|0:0" ]
  check $? "[$launcher] sacct -c (job completion log) says COMPLETED 0:0 (last record: ${comp:-none})"
  read -r d n <<< "$(done_cells "$map")"
  [ "$d" = "$cells" ] && [ "$n" = "$cells" ]
  check $? "[$launcher] the final map has all $cells cells done ($d of $n)"
  maps="$maps $map"
done

# --- the same scene in one uninterrupted run, straight under mpirun --------------------------
ref="$tmp/work/reference.h5"
log "reference: mpirun -n 2 vibromap sweep (no Slurm, no interruption)"
t_ref=$(date +%s)
root_flag=""
[ "$(id -u)" -eq 0 ] && root_flag=--allow-run-as-root
HWLOC_COMPONENTS=-gl,-opencl OMPI_MCA_pml=ob1 OMPI_MCA_btl=self,vader HDF5_USE_FILE_LOCKING=FALSE \
  mpirun $root_flag -n 2 "$exe" sweep "$scene" -o "$ref" --quiet > "$tmp/work/reference.log" 2>&1
rc=$?
log "reference: exit code $rc in $(( $(date +%s) - t_ref )) s"
check "$rc" "the reference run finished"

for map in $maps; do
  out=$(HDF5_USE_FILE_LOCKING=FALSE "$py" - "$map" "$ref" <<'EOF' 2>&1
import sys
import h5py
import numpy as np

def datasets(path):
    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return found

a, b = datasets(sys.argv[1]), datasets(sys.argv[2])
problems = []
if set(a) != set(b):
    problems.append("datasets only in one map: " + " ".join(sorted(set(a) ^ set(b))))
names = [n for n in sorted(set(a) & set(b)) if n.split("/")[-1] != "wall_s"]
for n in names:
    x, y = np.asarray(a[n]), np.asarray(b[n])
    if x.shape != y.shape or x.dtype != y.dtype:
        problems.append(f"{n}: {x.shape} {x.dtype} against {y.shape} {y.dtype}")
    elif not np.array_equal(x, y, equal_nan=x.dtype.kind in "fc"):
        diff = int(np.sum(~((x == y) | ((x != x) & (y != y))))) if x.dtype.kind in "fc" else int(np.sum(x != y))
        problems.append(f"{n}: {diff} values differ")
print(f"{len(names)} datasets compared (all but wall_s): {' '.join(names)}")
for p in problems:
    print("differs: " + p)
sys.exit(1 if problems else 0)
EOF
)
  rc=$?
  printf '%s\n' "$out" | sed 's/^/    /'
  check "$rc" "$(basename "$map") equals the uninterrupted run in every dataset but wall_s (NaN-aware)"
done

if [ "$failures" -eq 0 ]; then
  status=0
  log "all checks passed in $(elapsed) s"
  exit 0
fi
log "$failures check(s) failed; slurmctld log tail:"
tail -n 15 "$tmp/log/slurmctld.log" | sed 's/^/    /'
exit 1
