#!/usr/bin/env bash
# Prints SHA-256 fingerprints of what prt computes on the bundled data, at fixed seeds, so that a
# refactor can show it changed nothing: per-vertex coefficients (`prt info --csv`, 9 significant
# digits, enough to round-trip a float), metadata without its wall times, relit vertex colours
# (`prt relight --csv`, also for Haar files) and the environment's SH coefficients. The SH
# convention text is left out: it is printed identically by every command, and compared as such
# by the tests.
# Usage: scripts/behaviour-hashes.sh [PRT_BINARY] > hashes.txt
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prt="${1:-$root/build/bin/prt}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
scene="$root/data/demo.glb"
sky="$root/data/sky.hdr"

meta_without_times() {
  "$prt" info "$1" --json | python3 -c '
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items()
                if not (k.startswith("seconds") or k.endswith("_seconds")
                        or k in ("file", "bytes", "threads", "sh_basis"))}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
print(json.dumps(strip(json.load(sys.stdin)), sort_keys=True))'
}

sh_bake() {  # name, extra bake arguments
  local name="$1"; shift
  "$prt" bake "$scene" -o "$work/$name.prt" --quiet --seed 7 "$@"
  echo "$name coefficients $("$prt" info "$work/$name.prt" --csv | sha256sum | cut -c1-16)"
  echo "$name metadata     $(meta_without_times "$work/$name.prt" | sha256sum | cut -c1-16)"
  "$prt" relight "$scene" "$work/$name.prt" "$sky" -o "$work/$name.exr" --csv "$work/$name.csv" \
    >/dev/null 2>&1
  echo "$name relit        $(sha256sum < "$work/$name.csv" | cut -c1-16)"
}

sh_bake shadowed --transfer shadowed --order 5 --samples 256 --ao --bent-normals
sh_bake interreflected --transfer interreflected --order 4 --samples 128
sh_bake auto --auto --env "$sky" --tolerance 0.1
"$prt" bake "$scene" -o "$work/haar.prt" --quiet --seed 7 --basis haar --cube 8
"$prt" relight "$scene" "$work/haar.prt" "$sky" -o "$work/haar.exr" --csv "$work/haar.csv" \
  >/dev/null 2>&1
echo "haar relit        $(sha256sum < "$work/haar.csv" | cut -c1-16)"
"$prt" env "$sky" --order 5 --json | python3 -c '
import json, sys
d = json.load(sys.stdin)
print(json.dumps({k: v for k, v in d.items() if k not in ("sh_basis", "basis", "file")}, sort_keys=True))' \
  | sha256sum | sed 's/^\(.\{16\}\).*/env coefficients  \1/'
