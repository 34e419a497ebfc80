#!/usr/bin/env bash
# Runs a farm bake's N shards one after another on this machine, merges them, and reports what
# the split cost: each shard's wall and CPU time (user + sys) and peak memory, their sums, the
# merge's, and — with --single — the single `prt bake` with the same options, the extra work of
# the split ((Σ shards + merge) CPU / single CPU − 1) and a byte comparison of the two files
# (docs/FARM.md). Use it to measure the splitting overhead and the merge's share (Amdahl), or to
# try a farm bake without a scheduler.
#
# Usage: scripts/farm-sequential.sh [--single] [--lock FILE] PRT SCENE N OUT_DIR [bake options...]
#   --lock FILE: the single bake and the merge (the steps that hold the whole scene's gather)
#          run under `flock FILE`, the shards without it (one big run at a time on a shared box)
#   e.g. scripts/farm-sequential.sh --single build/bin/prt field.glb 4 out/farm4 \
#          --transfer interreflected --order 5 --samples 256
# Writes OUT_DIR/part_I.prtpart, OUT_DIR/merged.prt (and single.prt), OUT_DIR/times.tsv
# (step, wall s, user s, sys s, peak KB). Exit status 1 when a step fails or the merged file
# differs from the single bake.
set -euo pipefail
single=no lock=()
while [[ "${1:-}" == --single || "${1:-}" == --lock ]]; do
  if [[ "$1" == --single ]]; then single=yes; shift; continue; fi
  (($# >= 2)) || { echo "farm-sequential.sh: --lock needs a file" >&2; exit 2; }
  command -v flock > /dev/null || { echo "farm-sequential.sh: --lock needs flock (util-linux)" >&2; exit 2; }
  lock=(flock "$2")
  shift 2
done
if (($# < 4)); then
  sed -n '2,18p' "$0" >&2
  exit 2
fi
prt="$(realpath "$1")" scene="$2" n="$3" out="$4"
shift 4
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "farm-sequential.sh: N must be a positive integer" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "farm-sequential.sh: needs /usr/bin/time (Debian: time)" >&2; exit 2; }
mkdir -p "$out"
times="$out/times.tsv"
printf 'step\twall_s\tuser_s\tsys_s\tpeak_kb\n' > "$times"

# Runs a step under /usr/bin/time, appending its figures to times.tsv.
step() {  # name command...
  local name="$1"; shift
  local t="$out/.time" wrap=()
  [[ "$name" == single || "$name" == merge ]] && wrap=("${lock[@]}")  # waiting is not timed
  "${wrap[@]}" /usr/bin/time -f '%e\t%U\t%S\t%M' -o "$t" "$@" > "$out/$name.log" 2>&1 ||
    { echo "farm-sequential.sh: $name failed:" >&2; tail -3 "$out/$name.log" >&2; exit 1; }
  printf '%s\t%s\n' "$name" "$(cat "$t")" >> "$times"
  rm -f "$t"
}

if [[ $single == yes ]]; then
  step single "$prt" bake "$scene" "$@" -o "$out/single.prt"
fi
parts=()
for ((i = 0; i < n; ++i)); do
  parts+=("$out/part_$i.prtpart")
  step "shard$i" "$prt" bake "$scene" "$@" --shard "$i/$n" -o "$out/part_$i.prtpart"
done
step merge "$prt" merge "${parts[@]}" -o "$out/merged.prt"

awk -F'\t' -v n="$n" '
  NR == 1 { next }
  { cpu = $3 + $4 }
  $1 == "single" { have = 1; sw = $2; sc = cpu; sm = $5 }
  $1 ~ /^shard/ { hw += $2; hc += cpu; if ($5 > hm) hm = $5 }
  $1 == "merge" { mw = $2; mc = cpu; mm = $5 }
  END {
    printf "shards (%d, one after another): wall %.2f s, CPU %.2f s, peak %.0f MB (largest)\n", n, hw, hc, hm / 1024
    printf "merge + solve: wall %.2f s, CPU %.2f s, peak %.0f MB\n", mw, mc, mm / 1024
    if (have) {
      printf "single bake: wall %.2f s, CPU %.2f s, peak %.0f MB\n", sw, sc, sm / 1024
      printf "extra work of the split: %+.1f%% CPU (shards + merge against the single bake), %+.1f%% wall\n", (sc > 0 ? 100 * ((hc + mc) / sc - 1) : 0), (sw > 0 ? 100 * ((hw + mw) / sw - 1) : 0)
      printf "merge share: %.1f%% of the split'"'"'s CPU\n", (hc + mc > 0 ? 100 * mc / (hc + mc) : 0)
    }
  }' "$times"
if [[ $single == yes ]]; then
  if cmp -s "$out/single.prt" "$out/merged.prt"; then
    echo "merged.prt is byte-identical to single.prt"
  else
    echo "farm-sequential.sh: merged.prt differs from single.prt" >&2
    exit 1
  fi
fi
