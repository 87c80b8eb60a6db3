#!/usr/bin/env bash
# The render farm for real (ctest label "farm"): a one-node Slurm cluster on
# localhost (munged, slurmctld and slurmd with a generated slurm.conf, private
# ports, state and logs in a temporary folder) runs
# scripts/slurm/render_array.sbatch for a 12-frame sequence in 3 shards, and
# every frame must be byte-identical to a local run of the same sequence.
# Installs Debian's slurm-wlm and munge where missing (scripts/install-deps.sh
# --farm). When a daemon does not start, the test fails with its log: a skip
# would hide a broken farm path. Always stops the daemons it started.
# Usage: slurm_farm_test.sh QUADRA_BINARY SOURCE_DIR ASSETS_DIR
set -euo pipefail

quadra=$(realpath "$1") source_dir=$(realpath "$2") assets=$3
scene=$assets/BoxAnimated/glTF/BoxAnimated.gltf
size=(--width 160 --height 90)
range=0:11
shards=3
timeout_s=180

fail() {
  echo "slurm_farm_test: FAIL: $*" >&2
  exit 1
}

[ -f "$scene" ] || fail "no scene $scene (the shared assets beside the checkout)"

# The job script's task numbering, without Slurm: array 1-7:2 has tasks
# 1, 3, 5, 7, shards 0..3; a task off the range is an error.
array_script=$source_dir/scripts/slurm/render_array.sbatch
shard_of() {
  env SLURM_ARRAY_TASK_ID="$1" SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_STEP=2 \
    SLURM_ARRAY_TASK_COUNT=4 QUADRA=echo bash "$array_script" s.gltf 0:9 'f_#.exr' 2>&1 |
    sed -n 's/.*--shard \([^ ]*\) .*/\1/p'
}
[ "$(shard_of 5)" = 2/4 ] || fail "array task 5 of 1-7:2 is not shard 2/4: '$(shard_of 5)'"
[ "$(shard_of 1)" = 0/4 ] || fail "array task 1 of 1-7:2 is not shard 0/4: '$(shard_of 1)'"
SLURM_ARRAY_TASK_ID=4 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_STEP=2 SLURM_ARRAY_TASK_COUNT=4 \
  QUADRA=echo bash "$array_script" s.gltf 0:9 'f_#.exr' >/dev/null 2>&1 &&
  fail "array task 4 of 1-7:2 was accepted"
bash "$source_dir/scripts/install-deps.sh" --farm ||
  fail "could not install slurm-wlm and munge (scripts/install-deps.sh --farm)"

work=$(mktemp -d /tmp/quadra_farm.XXXXXX)
# munged requires its socket's folder to be searchable by everyone.
chmod 711 "$work"
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/log" "$work/local" "$work/farm"
chmod 711 "$work/munge"
ctld_pid='' slurmd_pid=''
export SLURM_CONF=$work/slurm.conf

show_logs() {
  for log in "$work"/log/*; do
    [ -f "$log" ] || continue
    echo "---- $log (last 40 lines)" >&2
    tail -n 40 "$log" >&2
  done
}

stop_pid() {
  local pid=$1
  [ -n "$pid" ] || return 0
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.2
  done
  kill -9 "$pid" 2>/dev/null || true
}

cleanup() {
  local status=$?
  set +e
  if [ -n "$ctld_pid" ]; then
    timeout 10 scancel --quiet --user="$(id -un)" >/dev/null 2>&1
  fi
  stop_pid "$slurmd_pid"
  stop_pid "$ctld_pid"
  [ -f "$work/munge/munged.pid" ] && stop_pid "$(cat "$work/munge/munged.pid")"
  wait 2>/dev/null
  ((status == 0)) || show_logs
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT

# A port nothing listens on (a refused connection), from a range above the
# usual ephemeral ports' start, so that this cluster meets no other.
free_port() {
  local port
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 20000))
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; then
      echo "$port"
      return 0
    fi
  done
  fail "found no free TCP port"
}
ctld_port=$(free_port)
slurmd_port=$(free_port)
while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done

started=$(date +%s)
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged --socket="$work/munge/munge.socket" --key-file="$work/munge/munge.key" \
  --log-file="$work/log/munged.log" --pid-file="$work/munge/munged.pid" \
  --seed-file="$work/munge/munged.seed" || fail "munged did not start"

node=$(hostname -s)
cat >"$SLURM_CONF" <<CONF
ClusterName=quadrafarm
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=quadra Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF

# -D: in the foreground, so that this script holds their process ids.
slurmctld -D -c -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
ctld_pid=$!
slurmd -D -f "$SLURM_CONF" >"$work/log/slurmd.out" 2>&1 &
slurmd_pid=$!

state=''
for _ in $(seq 60); do
  kill -0 "$ctld_pid" 2>/dev/null || fail "slurmctld exited (its log follows)"
  kill -0 "$slurmd_pid" 2>/dev/null || fail "slurmd exited (its log follows)"
  state=$(sinfo --noheader --nodes="$node" --format=%T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "node $node is '$state', not idle, 30 s after the daemons started"
echo "slurm_farm_test: cluster up in $(($(date +%s) - started)) s (ports $ctld_port, $slurmd_port)"

# The local run the farm's frames must equal.
"$quadra" render "$scene" "${size[@]}" --sequence "$range" --out "$work/local/box_####.exr" \
  >"$work/log/local.out" 2>&1 || fail "the local render failed"

submitted=$(date +%s)
export QUADRA=$quadra
# --wait: sbatch returns when every task has ended, with the highest exit
# status among them; timeout bounds the wait.
# One core per task: the tasks render with --threads 1, the local run with
# all cores, and the frames must still be the same bytes.
if ! timeout "$timeout_s" sbatch --wait --quiet --array=0-$((shards - 1)) --cpus-per-task=1 \
  --chdir="$work" \
  --output="$work/log/task_%a.out" "$source_dir/scripts/slurm/render_array.sbatch" \
  "$scene" "$range" "$work/farm/box_####.exr" "${size[@]}"; then
  squeue >&2 || true
  fail "the array job failed or did not end within $timeout_s s"
fi
echo "slurm_farm_test: array of $shards tasks ran in $(($(date +%s) - submitted)) s"

# Every frame, byte for byte; nothing else in the output folder (no temporaries).
frames=0
for local_frame in "$work"/local/box_*.exr; do
  name=$(basename "$local_frame")
  cmp "$local_frame" "$work/farm/$name" || fail "farm frame $name differs from the local run's"
  frames=$((frames + 1))
done
((frames == 12)) || fail "the local run wrote $frames frames, not 12"
farm_files=$(find "$work/farm" -type f | wc -l)
((farm_files == 12)) || fail "the farm wrote $farm_files files, not 12: $(ls "$work/farm")"
cmp -s "$work/local/box_0000.exr" "$work/local/box_0011.exr" &&
  fail "frames 0 and 11 are identical: the scene did not move, the test proves little"

# Each task rendered exactly its shard: frames k, k+3, k+6, k+9.
for ((k = 0; k < shards; ++k)); do
  rendered=$(sed -n 's/^quadra progress frame=\([0-9]*\) status=rendered .*/\1/p' \
    "$work/log/task_$k.out" | tr '\n' ' ')
  expected=$(seq -s ' ' "$k" "$shards" 11)
  [ "$rendered" = "$expected " ] ||
    fail "task $k rendered frames '$rendered', expected '$expected ' ($(cat "$work/log/task_$k.out"))"
  grep -q '^quadra frame_ms .* threads=1 ' "$work/log/task_$k.out" ||
    fail "task $k did not render with the 1 thread it was given"
done
echo "slurm_farm_test: PASS: 12 frames in $shards shards byte-identical to the local run" \
  "($(($(date +%s) - started)) s in all)"
