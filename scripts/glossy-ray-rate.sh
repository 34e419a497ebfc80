#!/usr/bin/env bash
# The glossy bake's ray rate against the diffuse bake's on the same scene, order and samples:
# the two bakes alternated RUNS times (the machines are noisy: compare within one run), printing
# each pass's rays and seconds ("rays in … s (… Mrays/s)") and the median ratio.
# Usage: scripts/glossy-ray-rate.sh PRT SCENE [ORDER=5] [SAMPLES=256] [THREADS=0] [RUNS=3]
set -euo pipefail
prt="$1" scene="$2" order="${3:-5}" samples="${4:-256}" threads="${5:-0}" runs="${6:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
rate() { grep -o '([0-9.]* Mrays/s)' | tr -d '()' | cut -d' ' -f1; }
ratios=()
for ((i = 0; i < runs; ++i)); do
  d=$("$prt" bake "$scene" -o "$work/d.prt" --transfer shadowed --order "$order" \
        --samples "$samples" --threads "$threads" | rate)
  g=$("$prt" bake "$scene" --glossy -o "$work/g.prtg" --order "$order" --samples "$samples" \
        --threads "$threads" | rate)
  r=$(awk -v g="$g" -v d="$d" 'BEGIN { printf "%.2f", g / d }')
  echo "run $i: diffuse $d Mrays/s, glossy $g Mrays/s, ratio $r"
  ratios+=("$r")
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{ a[NR] = $1 } END { print "median ratio " a[int((NR + 1) / 2)] }'
