#!/usr/bin/env bash
# A real single-machine Slurm (munged, slurmctld, slurmd from Debian's munge, slurmctld, slurmd and
# slurm-client, all in a temporary folder on free ports) runs `rayster farm slurm --submit`: a 3-task
# array of a tiny lavapipe render. One task's rayster is killed mid-run (SIGKILL, as the OOM killer
# would); the task requeues itself and resumes with --skip-existing. Every frame must then exist
# exactly once, with no temporary file left, and equal a single-process render bit for bit.
# Usage: test_farm_slurm.sh RAYSTER_BINARY. Exit 77 (ctest: skipped) with one line when this
# machine cannot run the daemons (not root, packages missing). Every exit path cancels the job and
# stops the daemons; a deadline bounds every wait.
set -euo pipefail
rayster=$1
skip() {
  echo "farm_slurm: skipped: $*"
  exit 77
}
[ "$(id -u)" = 0 ] || skip "slurmd must run as root"
for b in munged slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
  command -v "$b" >/dev/null 2>&1 || skip "$b is not installed (scripts/setup.sh: munge slurmctld slurmd slurm-client)"
done

deadline=$((SECONDS + ${RAYSTER_SLURM_TEST_SECONDS:-240}))
D=$(mktemp -d /tmp/rayster-slurm-XXXXXX)
chmod 755 "$D"  # munged wants every folder above its socket searchable
pids=()
job=""
passed=0
cleanup() {
  set +e
  if [ -n "$job" ]; then scancel "$job" 2>/dev/null; fi
  for _ in $(seq 1 20); do
    [ -z "$job" ] || [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
    sleep 0.5
  done
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null; done
  if [ "$passed" = 1 ]; then
    rm -rf "$D"
  else
    for f in "$D"/log/*.log "$D"/out/slurm/*.log; do
      [ -f "$f" ] && { echo "---- $f (last lines)"; tail -n 15 "$f"; }
    done
    echo "farm_slurm: FAILED; files kept in $D"
  fi
}
trap cleanup EXIT
trap 'exit 1' INT TERM
fail() {
  echo "farm_slurm: FAIL: $*"
  exit 1
}
waitFor() {  # waitFor WHAT COMMAND...: polls until COMMAND succeeds, failing at the deadline
  local what=$1
  shift
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || fail "timed out waiting for $what"
    sleep "${poll:-0.25}"
  done
}
freePort() {
  local p
  while :; do
    p=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
  done
}

# ---- the cluster: munge with its own key and socket, one controller, one node with one "GPU" ----
mkdir -m 755 "$D/munge" "$D/log"
mkdir -m 700 "$D/key" "$D/state"
mkdir -p "$D/spool/node"
dd if=/dev/urandom of="$D/key/munge.key" bs=1024 count=1 status=none
chmod 400 "$D/key/munge.key"
# `timeout` bounds each daemon's life even if this script is killed before its trap runs.
timeout 600 munged -F --key-file="$D/key/munge.key" --socket="$D/munge/socket" --pid-file="$D/munge/pid" \
  --seed-file="$D/key/seed" --log-file="$D/log/munged.log" >/dev/null 2>&1 &
pids+=($!)
waitFor "munged's socket" test -S "$D/munge/socket"

host=$(hostname -s)
cat >"$D/slurm.conf" <<EOF
ClusterName=rayster-test
SlurmctldHost=$host
SlurmctldPort=$(freePort)
SlurmdPort=$(freePort)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge/socket
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool/%n
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobRequeue=1
KillWait=5
GresTypes=gpu
NodeName=node NodeAddr=127.0.0.1 NodeHostname=$host CPUs=$(nproc) RealMemory=1000 Gres=gpu:1 State=UNKNOWN
PartitionName=test Nodes=node Default=YES MaxTime=INFINITE State=UP
EOF
# A gpu gres needs a device file; /dev/null stands in (rayster picks its own device here: no nvidia-smi).
echo "NodeName=node Name=gpu File=/dev/null" >"$D/gres.conf"
export SLURM_CONF=$D/slurm.conf  # the daemons find gres.conf beside it; the clients read it
timeout 600 slurmctld -D -f "$SLURM_CONF" >"$D/log/slurmctld.out" 2>&1 &
pids+=($!)
timeout 600 slurmd -D -f "$SLURM_CONF" -N node >"$D/log/slurmd.out" 2>&1 &
pids+=($!)
nodeIdle() { [ "$(sinfo -h -n node -o %T 2>/dev/null)" = idle ]; }
waitFor "the node to be idle (sinfo)" nodeIdle
echo "farm_slurm: cluster up after ${SECONDS} s"

# ---- the job: 12 frames of a tiny render in 3 chunks, one task at a time on the one "GPU" ----
# (40 accumulated frames make a frame take about 0.45 s on 2 cores: the kill below has frames to land between.)
render=(--size 64x48 --frames 40 --primary raster --indirect off)
frames=(0 1 2 3 4 5 6 7 8 9 10 11)
job=$("$rayster" farm slurm builtin:cornell --frames-out 0:11 --chunk 4 -o "$D/out/f_####.png" --job-name farmtest \
  --submit -- "${render[@]}")
[[ "$job" =~ ^[0-9]+$ ]] || fail "farm slurm --submit printed '$job', not a job id"
echo "farm_slurm: submitted job array $job"

# Task 1 (frames 4-7): kill its rayster once its first frame is written and before its last.
taskPid() { pgrep -f -- "--frames-out 4:7:1 -o $D/out/" | head -n 1; }
firstFrameOfTask1() {
  [ ! -f "$D/out/f_0007.png" ] || fail "task 1 finished before it could be killed: make its frames slower"
  [ -f "$D/out/f_0004.png" ] && [ -n "$(taskPid)" ]
}
poll=0.05 waitFor "task 1 to write its first frame" firstFrameOfTask1
kill -KILL "$(taskPid)"
[ ! -f "$D/out/f_0007.png" ] || fail "task 1 finished before it was killed: make its frames slower"
echo "farm_slurm: killed task 1's rayster after frame 4 at ${SECONDS} s"

# It requeues itself (exit 137: a signal is retryable); Slurm holds a requeued job about two minutes
# before it may start again, which the test does not wait for.
requeued() { scontrol show job "${job}_1" 2>/dev/null | grep -q "Restarts=1" && scontrol show job "${job}_1" | grep -q "JobState=PENDING"; }
waitFor "task 1 to requeue itself" requeued
scontrol update JobId="${job}_1" StartTime=now
arrayDone() { [ -z "$(squeue -h -j "$job" 2>/dev/null)" ]; }
waitFor "the array to finish" arrayDone
echo "farm_slurm: array done at ${SECONDS} s"

states=$(scontrol show job "$job" | grep -o "JobState=[A-Z]*" | sort | uniq -c | tr -s ' ')
[ "$(scontrol show job "$job" | grep -c "JobState=COMPLETED")" = 3 ] || fail "not 3 completed tasks: $states"
log1=$(ls "$D"/out/slurm/farmtest_"${job}"_1.log)
grep -q "exited with code 137 (retryable): requeueing, restart 1 of 3" "$log1" || fail "task 1 did not requeue: $log1"
[ "$(grep -c "frames 4:7:1" "$log1")" = 2 ] || fail "task 1 did not run twice into one log"
grep -q "skipped" "$log1" || fail "task 1's second run skipped nothing"

# Every frame once, nothing else; and equal to one process rendering the whole range.
listing=$(cd "$D/out" && ls -A | grep -v '^slurm$' | tr '\n' ' ')
expected=$(for f in "${frames[@]}"; do printf 'f_%04d.png ' "$f"; done)
[ "$listing" = "$expected" ] || fail "the frames are '$listing', expected '$expected'"
"$rayster" render builtin:cornell "${render[@]}" --frames-out 0:11 -o "$D/ref/f_####.png" --progress off ||
  fail "the single-process render failed"
for f in "${frames[@]}"; do
  name=$(printf 'f_%04d.png' "$f")
  cmp -s "$D/out/$name" "$D/ref/$name" || fail "$name differs from the single-process render"
done
passed=1
echo "farm_slurm: passed in ${SECONDS} s (12 frames, 3 tasks, task 1 killed and requeued)"
