#!/usr/bin/env bash
# The Slurm round trip of samples/slurm/sweep_array.sbatch on a single-node cluster brought up
# here, on loopback, by this script alone: its own munge key and socket, its own slurm.conf
# (free ports, state and spool folders in a temporary folder), munged, slurmctld and slurmd
# started as the current user and always stopped on exit. It submits a 3-task array of a small
# sweep, waits (bounded), merges the shards and compares the file with the local run, byte for
# byte (SOURCE_DATE_EPOCH). Where a daemon cannot start (no Slurm installed, no privileges,
# a container without what slurmd needs) it prints "SKIP: <reason>" and exits 77 (CTest skip).
# Usage: sweep_slurm_test.sh path/to/dimerlab REPO_ROOT
set -u
BIN=$(realpath "$1")
ROOT=$(realpath "$2")
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  command -v "$tool" >/dev/null 2>&1 || [ -x "/usr/sbin/$tool" ] ||
    skip "$tool not found (Debian packages slurm-wlm and munge)"
done
export PATH="$PATH:/usr/sbin"
WORK=$(mktemp -d /tmp/dimerlab_slurm.XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  sleep 0.5
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
  rm -rf "$WORK"
}
trap cleanup EXIT
cd "$WORK" || exit 1
export SOURCE_DATE_EPOCH=1700000000

# A free loopback port: nothing answers on it.
free_port() {
  local p
  for _ in $(seq 1 200); do
    p=$((20000 + RANDOM % 40000))
    (echo >/dev/tcp/127.0.0.1/$p) 2>/dev/null || { echo "$p"; return; }
  done
  echo 0
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
[ "$slurmd_port" != "$ctld_port" ] || slurmd_port=$((ctld_port + 1))
host=$(hostname -s)
user=$(id -un)
cpus=$(nproc)
mkdir -p state spool log out
chmod 700 "$WORK"

# munge: own key, socket, pid, log and seed files.
dd if=/dev/urandom of=munge.key bs=1024 count=1 status=none
chmod 400 munge.key
munged -F --force --socket="$WORK/munge.sock" --key-file="$WORK/munge.key" \
  --pid-file="$WORK/munged.pid" --log-file="$WORK/log/munged.log" \
  --seed-file="$WORK/munged.seed" >log/munged.out 2>&1 &
pids+=($!)
for _ in $(seq 1 50); do [ -S munge.sock ] && break; sleep 0.1; done
[ -S munge.sock ] || skip "munged did not start: $(tail -n 2 log/munged.log log/munged.out 2>/dev/null | tr '\n' ' ')"

cat >slurm.conf <<CONF
ClusterName=dimerlabtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
AuthInfo=socket=$WORK/munge.sock
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
SwitchType=switch/none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$WORK/slurm.conf

slurmctld -D -i -f "$SLURM_CONF" >log/slurmctld.out 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >log/slurmd.out 2>&1 &
pids+=($!)
state=
for _ in $(seq 1 300); do   # 30 s
  for p in "${pids[@]}"; do
    kill -0 "$p" 2>/dev/null ||
      skip "a Slurm daemon exited at start: $(tail -n 3 log/slurmctld.log log/slurmd.log log/*.out 2>/dev/null | grep -i -m2 -E 'error|fatal' | tr '\n' ' ')"
  done
  state=$(sinfo -h -N -o %T 2>/dev/null | head -n 1)
  [ "$state" = idle ] && break
  sleep 0.1
done
[ "$state" = idle ] || skip "the node did not become idle in 30 s (state '$state'): $(grep -i -m2 -E 'error|fatal' log/slurmd.log log/slurmctld.log | tr '\n' ' ')"
echo "cluster up: $host, slurmctld :$ctld_port, slurmd :$slurmd_port, $cpus CPUs"

cat >small.sweep <<SPEC
# 6 points, short windows: a round trip, not physics
ar = 3.9,5,6.1
gamma = 0.8,0.9
periods = 20
transient = 10
SPEC
"$BIN" sweep --spec small.sweep --threads 2 -q -o local.h5 >/dev/null || fail "local run"

job=$(sbatch --parsable --array=1-3 --chdir="$WORK" \
  --export=ALL,SWEEP_SPEC="$WORK/small.sweep",SWEEP_OUT="$WORK/out",DIMERLAB="$BIN" \
  "$ROOT/samples/slurm/sweep_array.sbatch" 2>sbatch.err) || fail "sbatch: $(cat sbatch.err)"
job=${job%%;*}
echo "submitted array job $job"
for _ in $(seq 1 1200); do   # 120 s
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 0.1
done
[ -z "$(squeue -h -j "$job" 2>/dev/null)" ] || fail "the array did not finish in 120 s: $(squeue -j "$job")"
for k in 1 2 3; do
  [ -s "out/shard_$k.h5" ] || fail "task $k wrote no shard: $(cat dimerlab-sweep_"${job}"_$k.log 2>/dev/null)"
done
"$BIN" merge out/shard_1.h5 out/shard_2.h5 out/shard_3.h5 -o merged.h5 || fail "merge"
cmp local.h5 merged.h5 || fail "the merged Slurm shards differ from the local run"
echo "ok: 3 Slurm array tasks, merged, identical to the local run"
