#!/usr/bin/env bash
# The Slurm example (examples/slurm/) on a real single-node Slurm: scripts/slurm-local.sh starts
# munged, slurmctld and slurmd in a scratch folder (its own ports), examples/slurm/submit.sh submits
# a job array of 3 shard bakes and the merge after it (--dependency=afterok), squeue waits for them,
# and the merged file must equal, byte for byte, one `prt bake` with the same options. Then again
# with one array task cancelled (scancel) while its prt bakes (frozen by SIGSTOP once its log shows
# a progress line, so that the cancellation lands mid-bake on a machine of any speed; scancel sends
# SIGCONT, SIGTERM, SIGKILL): the task must end CANCELLED without a part, the merge must be left
# waiting (DependencyNeverSatisfied), and the rerun of that shard alone (submit.sh --tasks 1) with
# its merge must still give the same bytes. Each task's log must show prt's progress lines.
# Finished jobs' states come from the cluster's jobcomp/filetxt record (sacct needs slurmdbd, which
# the local cluster has not; scripts/slurm-local.sh says why).
# Skips (77), saying why, when the cluster cannot start here (not root, slurm-wlm or munge missing,
# a daemon that refuses); PRT_REQUIRE_SLURM=1 makes that a failure. Daemons and the scratch folder
# are removed on every exit path. About 25 s on the shared 2-core machine.
# Usage: check_slurm_farm.sh PRT_BINARY SOURCE_DIR
set -euo pipefail
prt="$(realpath "$1")"
source_dir="$(realpath "$2")"
# /tmp, not the build folder: munge's socket path must be short.
scratch="$(mktemp -d /tmp/prt-slurm-farm.XXXXXX)"
cleanup() {
  "$source_dir/scripts/slurm-local.sh" stop "$scratch/cluster" || true
  rm -rf "$scratch"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

status=0
"$source_dir/scripts/slurm-local.sh" start "$scratch/cluster" >/dev/null 2>"$scratch/start.log" ||
  status=$?
if [[ $status -ne 0 ]]; then
  if [[ $status -eq 77 && "${PRT_REQUIRE_SLURM:-0}" != 1 ]]; then
    echo "SKIP: no local Slurm cluster here: $(head -1 "$scratch/start.log")"
    exit 77
  fi
  cat "$scratch/start.log"
  echo "FAIL: scripts/slurm-local.sh start exited with status $status"
  exit 1
fi
export SLURM_CONF="$scratch/cluster/slurm.conf"
jobcomp="$scratch/cluster/log/jobcomp.txt"
echo "ok: local Slurm cluster up ($(sinfo -h -o '%P %D node(s) %c CPUs %T'))"

fail() { echo "FAIL: $*"; exit 1; }

# The bake field at 30k vertices, interreflected: about 1 s of one core per shard.
# --cpus-per-task=1: one thread per task, two tasks at once on two cores.
scene="$scratch/field.glb"
"$prt" make-scene --scene field --vertices 30000 -o "$scene" >/dev/null
export PRT="$prt" PRT_SCENE="$scene" PRT_SHARDS=3 PRT_PROGRESS_INTERVAL=0
export PRT_BAKE_OPTIONS="--transfer interreflected --order 3 --samples 512 --seed 7"
export PRT_SBATCH_OPTIONS="--cpus-per-task=1"
# The single-process reference, baked while the cluster works on the first run.
# shellcheck disable=SC2086
"$prt" bake "$scene" $PRT_BAKE_OPTIONS --quiet -o "$scratch/single.prt" &
single_pid=$!

# Waits until none of the jobs is pending or running (squeue lists only those), 90 s at most.
wait_jobs() {  # jobid...
  local ids i
  ids="$(IFS=,; echo "$*")"
  for ((i = 0; i < 900; i++)); do
    [[ -z "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ]] && return 0
    sleep 0.1
  done
  squeue -j "$ids"
  fail "jobs $ids still queued after 90 s"
}

# The final state of job JOBID (array task TASK) from the jobcomp record.
state_of() {  # jobid [task]
  local pattern="^JobId=$1 "
  [[ $# -ge 2 ]] && pattern="ArrayJobId=$1 ArrayTaskId=$2 "
  grep -E "$pattern" "$jobcomp" | tail -1 | grep -o 'JobState=[A-Z_]*' | cut -d= -f2
}

submit() {  # work_dir [submit.sh options]
  PRT_WORK_DIR="$1" PRT_OUTPUT="$1/merged.prt" "$source_dir/examples/slurm/submit.sh" "${@:2}" \
    >"$1.ids"
  array="$(awk '$1 == "array" { print $2 }' "$1.ids")"
  merge="$(awk '$1 == "merge" { print $2 }' "$1.ids")"
  [[ -n "$array" && -n "$merge" ]] || fail "submit.sh printed no job ids: $(cat "$1.ids")"
}

same_as_single() {  # label merged
  wait "$single_pid" 2>/dev/null || true
  [[ -f "$scratch/single.prt" ]] || fail "the single-process bake wrote nothing"
  [[ -f "$2" ]] || fail "$1: the merge wrote no $2 (merge log: $(cat "$(dirname "$2")"/logs/merge_*.log))"
  cmp -s "$2" "$scratch/single.prt" ||
    fail "$1: the merged file differs from the single-process bake ($(cmp "$2" "$scratch/single.prt" 2>&1 | head -1))"
  echo "ok: $1: the merged file equals the single-process bake ($(stat -c %s "$2") bytes)"
}

# Run 1: the array and its merge.
run1="$scratch/run1"
submit "$run1"
wait_jobs "$array" "$merge"
for task in 0 1 2; do
  [[ "$(state_of "$array" "$task")" == COMPLETED ]] ||
    fail "run 1: array task ${array}_$task ended $(state_of "$array" "$task")"
  grep -q '%' "$run1/logs/bake_${array}_$task.log" ||
    fail "run 1: the log of task $task has no progress line: $(cat "$run1/logs/bake_${array}_$task.log")"
done
[[ "$(state_of "$merge")" == COMPLETED ]] || fail "run 1: merge job $merge ended $(state_of "$merge"): $(tail -2 "$run1/logs/merge_$merge.log")"
same_as_single "3 shards on Slurm, then the merge" "$run1/merged.prt"

# Run 2: task 1 is cancelled while its prt runs, then rerun alone.
run2="$scratch/run2"
submit "$run2"
part1="$run2/parts/part_0001.prtpart"
log1="$run2/logs/bake_${array}_1.log"
# Once task 1's log shows prt baking (a progress line), its prt is frozen (SIGSTOP) so that the
# cancellation lands mid-bake however fast the machine; scancel sends SIGCONT, SIGTERM, SIGKILL.
pid=""
for ((i = 0; i < 3000; i++)); do
  if grep -qs '^bake: .*%' "$log1"; then pid="$(pgrep -f -- "-o $part1\$" || true)"; fi
  [[ -n "$pid" || -f "$part1" ]] && break
  sleep 0.02
done
[[ -n "$pid" ]] || fail "run 2: task ${array}_1's prt was not seen baking (log: $(cat "$log1" 2>&1))"
kill -STOP $pid
progress="$(grep '^bake: .*%' "$log1" | tail -1 | sed 's/  */ /g')"
[[ ! -f "$part1" ]] || fail "run 2: task 1 finished before it could be cancelled (make its bake longer)"
scancel "${array}_1"
wait_jobs "$array"
[[ "$(state_of "$array" 1)" == CANCELLED ]] || fail "run 2: task ${array}_1 ended $(state_of "$array" 1), not CANCELLED"
[[ ! -f "$part1" ]] || fail "run 2: the cancelled task left a part"
for task in 0 2; do
  [[ "$(state_of "$array" "$task")" == COMPLETED ]] ||
    fail "run 2: array task ${array}_$task ended $(state_of "$array" "$task")"
done
reason=""
for ((i = 0; i < 100; i++)); do
  reason="$(squeue -h -j "$merge" -o %r)"
  [[ "$reason" == DependencyNeverSatisfied ]] && break
  sleep 0.1
done
[[ "$reason" == DependencyNeverSatisfied ]] ||
  fail "run 2: the merge after a cancelled task is '$reason', not waiting forever"
[[ ! -f "$run2/merged.prt" ]] || fail "run 2: a merge ran although a shard was cancelled"
echo "ok: task ${array}_1 cancelled mid-bake (at '$progress'): no part, the merge held (DependencyNeverSatisfied)"
scancel "$merge"
old_array="$array"
submit "$run2" --tasks 1
wait_jobs "$array" "$merge"
[[ "$(state_of "$array" 1)" == COMPLETED ]] || fail "run 2: the rerun ${array}_1 ended $(state_of "$array" 1)"
[[ "$(state_of "$merge")" == COMPLETED ]] || fail "run 2: merge job $merge ended $(state_of "$merge"): $(tail -2 "$run2/logs/merge_$merge.log")"
same_as_single "task ${old_array}_1 cancelled, rerun alone as ${array}_1, merged" "$run2/merged.prt"
