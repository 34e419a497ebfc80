#!/usr/bin/env bash
# Start-up cost of each prt command: wall time, CPU time (user + sys) and peak memory of small
# runs, the median of 5, for one or more prt binaries run alternately (the machines are noisy:
# compare binaries within one run). Usage: scripts/startup-times.sh PRT [PRT ...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
first="$1"
"$first" bake "$root/data/demo.glb" -o "$work/demo.prt" --order 2 --samples 16 --quiet
"$first" relight "$root/data/demo.glb" "$work/demo.prt" "$root/data/sky.hdr" -o "$work/sky.exr" \
  --quiet --size 64x32 >/dev/null 2>&1 || true
declare -A commands=(
  [info]="info $work/demo.prt"
  [env-hdr]="env $root/data/sky.hdr --order 3"
  [env-exr]="env $work/sky.exr --order 3"
  [bake-small]="bake $root/data/demo.glb -o $work/b.prt --order 1 --samples 16 --quiet"
  [help]="--help"
)
printf '%-10s' command
for b in "$@"; do printf ' | %-36s' "$b"; done
printf '\n'
for name in info env-hdr env-exr bake-small help; do
  printf '%-10s' "$name"
  for b in "$@"; do
    rows=()
    for _ in 1 2 3 4 5; do
      /usr/bin/time -o "$work/time" -f '%e %U %S %M' $b ${commands[$name]} >/dev/null 2>&1 || true
      rows+=("$(tail -1 "$work/time")")
    done
    printf '%s\n' "${rows[@]}" | sort -n | sed -n 3p |
      awk '{printf " | wall %5.2f s cpu %5.2f s %7.0f MB    ", $1, $2 + $3, $4 / 1024}'
  done
  printf '\n'
done
