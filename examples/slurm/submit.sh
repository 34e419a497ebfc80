#!/usr/bin/env bash
# Submits a sharded prt bake to Slurm: a job array of N bake tasks (bake_array.sbatch), then the
# merge (merge.sbatch) with --dependency=afterok on the array, so that it starts only when every
# shard has succeeded. Prints "array JOBID" and "merge JOBID".
#
# Usage: examples/slurm/submit.sh [--tasks LIST]
#   --tasks LIST  submit only these shards (Slurm's array syntax: 2, 1,3 or 0-2) and a merge
#                 after them: the rerun of shards that failed, were cancelled or lost their node.
#                 The other parts stay as they are. A merge left waiting on the failed array
#                 (reason DependencyNeverSatisfied) will never start: scancel it.
# Environment:
#   PRT_SCENE           the scene (required)
#   PRT_OUTPUT          the merged file to write (required)
#   PRT_SHARDS          N, the number of shards (default 4; the same N for a rerun)
#   PRT_BAKE_OPTIONS    prt bake's options, split at spaces (default none), e.g.
#                       "--transfer interreflected --order 5 --samples 256"
#   PRT                 the prt program (default: prt on the PATH)
#   PRT_WORK_DIR        a folder every node can reach, for parts/ and logs/ (default
#                       OUTPUT.farm beside the output)
#   PRT_SBATCH_OPTIONS  more sbatch options for both jobs, split at spaces (partition, account,
#                       time limit, --cpus-per-task: prt then takes that many threads)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

tasks=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --tasks) [[ $# -ge 2 ]] || { echo "submit.sh: --tasks needs a list" >&2; exit 2; }
      tasks="$2"; shift 2 ;;
    *) echo "usage: examples/slurm/submit.sh [--tasks LIST]" >&2; exit 2 ;;
  esac
done
: "${PRT_SCENE:?set PRT_SCENE to the scene to bake}"
: "${PRT_OUTPUT:?set PRT_OUTPUT to the merged file to write}"
export PRT_SHARDS="${PRT_SHARDS:-4}"
[[ "$PRT_SHARDS" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: PRT_SHARDS=$PRT_SHARDS is not a count" >&2; exit 2; }
[[ -f "$PRT_SCENE" ]] || { echo "submit.sh: $PRT_SCENE: no such file" >&2; exit 2; }

# Absolute paths: the jobs may start in another folder, on another node.
absolute() { [[ "$1" = /* ]] && echo "$1" || echo "$PWD/$1"; }
export PRT_SCENE="$(absolute "$PRT_SCENE")"
export PRT_OUTPUT="$(absolute "$PRT_OUTPUT")"
export PRT_WORK_DIR="$(absolute "${PRT_WORK_DIR:-$PRT_OUTPUT.farm}")"
prt="${PRT:-prt}"
if [[ "$prt" == */* ]]; then
  prt="$(absolute "$prt")"
else
  prt="$(command -v "$prt")" || { echo "submit.sh: no $prt on the PATH (set PRT)" >&2; exit 2; }
fi
[[ -x "$prt" ]] || { echo "submit.sh: $prt is not a program" >&2; exit 2; }
export PRT="$prt"
export PRT_BAKE_OPTIONS="${PRT_BAKE_OPTIONS:-}"
mkdir -p "$PRT_WORK_DIR/parts" "$PRT_WORK_DIR/logs"

# shellcheck disable=SC2206  # a list of options, split at spaces
extra=(${PRT_SBATCH_OPTIONS:-})
array_job="$(sbatch --parsable "${extra[@]}" --array="${tasks:-0-$((PRT_SHARDS - 1))}" \
  --output="$PRT_WORK_DIR/logs/bake_%A_%a.log" "$here/bake_array.sbatch")"
array_job="${array_job%%;*}"  # --parsable prints JOBID[;CLUSTER]
merge_job="$(sbatch --parsable "${extra[@]}" --dependency="afterok:$array_job" \
  --output="$PRT_WORK_DIR/logs/merge_%j.log" "$here/merge.sbatch")"
merge_job="${merge_job%%;*}"
echo "array $array_job"
echo "merge $merge_job"
