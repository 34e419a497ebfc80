#!/usr/bin/env bash
# scripts/farm-sequential.sh on a tiny field scene (3 shards, interreflected, 16 samples): it runs,
# prints its summary lines, writes times.tsv with every step, and the merged file is the single
# bake's (the single bake and the merge under --lock). A few seconds.
# Usage: check_farm_sequential.sh PRT_BINARY SOURCE_DIR
set -euo pipefail
prt="$(realpath "$1")"
source_dir="$(realpath "$2")"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
"$prt" make-scene --scene field --vertices 600 -o "$scratch/field.glb" > /dev/null
summary=$(bash "$source_dir/scripts/farm-sequential.sh" --single --lock "$scratch/lock" "$prt" "$scratch/field.glb" 3 \
  "$scratch/out" --transfer interreflected --samples 16)
echo "$summary"
failures=0
for line in "shards (3, one after another)" "merge + solve" "single bake" "extra work of the split" \
  "merged.prt is byte-identical to single.prt"; do
  grep -qF "$line" <<< "$summary" || { echo "FAIL: no line '$line'"; failures=$((failures + 1)); }
done
steps=$(cut -f1 "$scratch/out/times.tsv" | tr '\n' ' ')
[[ "$steps" == "step single shard0 shard1 shard2 merge " ]] ||
  { echo "FAIL: times.tsv steps: $steps"; failures=$((failures + 1)); }
((failures == 0)) && echo "farm-sequential.sh works"
exit $((failures > 0))
