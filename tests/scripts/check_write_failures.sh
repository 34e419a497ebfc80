#!/usr/bin/env bash
# A write that fails leaves nothing behind: each command below runs with its file size limited
# (ulimit -f, SIGXFSZ ignored, so a write past the limit fails with EFBIG as on a full disk) and
# must exit with status 1, print one line naming the file and the problem ("File too large"), and
# leave neither the output, nor its temporary (OUT.tmp-*), nor its run record (OUT.run.json).
# The same for `--memory-limit 1K`: the bake stops before anything is written (status 1, one
# line naming the scene and the limit), and a value that is not a size is a usage error (status 2).
# And a full disk (a small tmpfs) under an interreflected glossy bake and its scratch files.
# Covers bake (SH), bake --glossy, compress, radiosity --per-emitter / --csv / --vertex-colors /
# --form-factor-cache (dense and the hierarchical link cache), make-scene, export-gltf, bake
# --shard and radiosity --shard (part files) and merge. A few seconds.
# Usage: check_write_failures.sh PRT_BINARY
set -euo pipefail
prt="$(realpath "$1")"
fixtures="$(cd "$(dirname "$0")" && pwd)/fixtures"  # room.obj: a lit room, two emitters
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Inputs, made without a limit.
"$prt" make-scene --scene glossy -o glossy.glb >/dev/null
"$prt" bake glossy.glb --glossy -o glossy.prtg --order 2 --samples 16 --quiet
cp "$fixtures/room.obj" "$fixtures/room.mtl" .

# Runs prt with files limited to KB kilobytes; OUTPUT is the file that cannot be written.
limited() {  # kilobytes output args...
  local kilobytes="$1" output="$2"; shift 2
  local status=0
  (trap '' XFSZ; ulimit -f "$kilobytes"; exec "$prt" "$@") >/dev/null 2>err.txt || status=$?
  expect_refusal "prt $* (files limited to ${kilobytes} KB)" 1 "$output" "File too large"
  [[ $status == 1 ]] || fail "prt $*: exit status $status, expected 1"
}

# After a refused run: one line on stderr naming OUTPUT and containing PROBLEM, and no OUTPUT,
# OUTPUT.tmp-* or OUTPUT.run.json.
expect_refusal() {  # label status output problem [name in the message, default output]
  local label="$1" output="$3" problem="$4" named="${5:-$3}" before=$failures
  local lines
  lines=$(wc -l < err.txt)
  [[ $lines == 1 ]] || fail "$label: $lines lines on stderr: $(cat err.txt)"
  grep -q -- "$named" err.txt || fail "$label: the message does not name $named: $(cat err.txt)"
  grep -q -- "$problem" err.txt || fail "$label: the message does not say '$problem': $(cat err.txt)"
  local left
  left=$(ls -d "$output" "$output".tmp-* "$output".run.json 2>/dev/null || true)
  [[ -z "$left" ]] || fail "$label: left behind: $left"
  ((failures > before)) || echo "ok: $label: $(cat err.txt)"
}

limited 64 shadowed.prt bake glossy.glb -o shadowed.prt --order 3 --samples 16 --quiet
limited 64 glossy-out.prtg bake glossy.glb --glossy -o glossy-out.prtg --order 2 --samples 16 \
  --quiet
limited 16 glossy.prtq compress glossy.prtg -o glossy.prtq --clusters 2 --vectors 2 --quiet
limited 4 room.prte radiosity room.obj --max-edge 0.25 --per-emitter room.prte --quiet
limited 4 room.csv radiosity room.obj --max-edge 0.25 --csv room.csv --quiet
limited 4 room.glb radiosity room.obj --max-edge 0.25 --vertex-colors room.glb --quiet
# The cache is written before the image, which fits.
limited 64 room.ffc radiosity room.obj --max-edge 0.1 --form-factor-cache room.ffc \
  -o room.png --size 8x6 --quiet
rm -f room.png room.png.run.json
# The hierarchical solver's link cache, written before the CSV.
limited 64 room.links radiosity room.obj --max-edge 0.1 --solver hierarchical \
  --form-factor-cache room.links --csv room.csv --quiet
rm -f room.csv room.csv.run.json
limited 64 scene.glb make-scene -o scene.glb
"$prt" bake glossy.glb -o sh.prt --order 3 --samples 16 --quiet
limited 16 export.glb export-gltf glossy.glb sh.prt -o export.glb --quiet
# Farm bakes: a shard's part file, and the merge of the parts.
"$prt" make-scene --scene field --vertices 2000 -o field.glb >/dev/null
for i in 0 1; do
  "$prt" bake field.glb --transfer interreflected --samples 32 --shard "$i/2" -o "p$i.prtpart" \
    --quiet
done
limited 16 part.prtpart bake field.glb --transfer interreflected --samples 32 --shard 1/2 \
  -o part.prtpart --quiet
limited 16 merged.prt merge p0.prtpart p1.prtpart -o merged.prt --quiet
# Glossy shards (the merge streams the .prtg as the single bake does).
for i in 0 1; do
  "$prt" bake glossy.glb --glossy --order 3 --samples 16 --transfer interreflected --bounces 1 \
    --shard "$i/2" -o "g$i.prtpart" --quiet
done
limited 16 gpart.prtpart bake glossy.glb --glossy --order 3 --samples 16 --transfer \
  interreflected --bounces 1 --shard 0/2 -o gpart.prtpart --quiet
limited 16 gmerged.prtg merge g0.prtpart g1.prtpart -o gmerged.prtg --quiet
# Form-factor shards of prt radiosity, and their merge into a form-factor cache.
for i in 0 1; do
  "$prt" radiosity room.obj --max-edge 0.1 --shard "$i/2" -o "ff$i.prtpart" --quiet
done
limited 64 ffpart.prtpart radiosity room.obj --max-edge 0.1 --shard 0/2 -o ffpart.prtpart --quiet
limited 64 merged.ffc merge ff0.prtpart ff1.prtpart -o merged.ffc --quiet

# --memory-limit: too small for the coefficients (V × channels × order² × 4 bytes).
status=0
"$prt" bake glossy.glb -o small.prt --order 3 --samples 16 --memory-limit 1K --quiet \
  >/dev/null 2>err.txt || status=$?
[[ $status == 1 ]] || fail "bake --memory-limit 1K: exit status $status, expected 1"
expect_refusal "bake --memory-limit 1K" 1 small.prt "memory limit is 1.0 KB" glossy.glb
# Every kind of work that takes --memory-limit charges its large buffers before allocating them.
over_limit() {  # label output named args...
  local label="$1" output="$2" named="$3"
  shift 3
  status=0
  "$prt" "$@" --memory-limit 1K --quiet >/dev/null 2>err.txt || status=$?
  [[ $status == 1 ]] || fail "$label --memory-limit 1K: exit status $status, expected 1"
  expect_refusal "$label --memory-limit 1K" 1 "$output" "memory limit is 1.0 KB" "$named"
}
over_limit "bake --transfer interreflected" small.prt glossy.glb \
  bake glossy.glb -o small.prt --transfer interreflected --order 3 --samples 16
over_limit "bake --auto" small.prt glossy.glb bake glossy.glb -o small.prt --auto
over_limit "bake --glossy" small.prtg glossy.glb bake glossy.glb --glossy -o small.prtg --order 2
over_limit "bake --basis haar --transfer interreflected" small.prt glossy.glb \
  bake glossy.glb --basis haar --transfer interreflected -o small.prt --cube 8
over_limit "compress" small.prtq glossy.prtg compress glossy.prtg -o small.prtq --clusters 2 \
  --vectors 2
for solver in gauss-seidel progressive hierarchical; do
  over_limit "radiosity --solver $solver" room.csv room.obj radiosity room.obj --solver $solver \
    --max-edge 0.25 \
    --csv room.csv
done
# A full disk: a small tmpfs in a private mount namespace (skipped where the system allows none).
# An interreflected glossy bake keeps scratch files beside its output and reserves their blocks
# before its ray pass, so a disk too small for them stops it there ("cannot size a scratch
# file"), not at a write after the pass; a disk with room for them but not for the output fails
# at the output's write. Either way: status 1, one line, and nothing left on the disk.
# glossy.glb at order 3: the output is 7.9 MB (0.5 MB before the matrices), the scratch files
# 10.5 MB (float bounce) or 18.3 MB (binary16 bounce).
full_disk() {  # megabytes problem named args...
  local megabytes="$1" problem="$2" named="$3" before=$failures
  shift 3
  rm -rf disk left.txt status.txt
  mkdir disk
  unshare -m bash -c 'mount -t tmpfs -o "size=$1M" tmpfs disk || exit 9
    cp glossy.glb disk/ && cd disk && shift && status=0
    "$@" --quiet >/dev/null 2>../err.txt || status=$?
    echo "$status" >../status.txt
    ls -A | grep -v -x glossy.glb >../left.txt || true' _ "$megabytes" "$prt" "$@"
  local label="prt $* (a disk of $megabytes MB)" status
  status=$(cat status.txt)
  [[ $status == 1 ]] || fail "$label: exit status $status, expected 1"
  [[ $(wc -l < err.txt) == 1 ]] || fail "$label: stderr: $(cat err.txt)"
  grep -q -- "$named" err.txt || fail "$label: the message does not name $named: $(cat err.txt)"
  grep -q -- "$problem" err.txt || fail "$label: the message does not say '$problem': $(cat err.txt)"
  [[ ! -s left.txt ]] || fail "$label: left behind: $(cat left.txt)"
  ((failures > before)) || echo "ok: $label: $(cat err.txt)"
}
mkdir probe
if unshare -m bash -c 'mount -t tmpfs -o size=1M tmpfs probe' 2>/dev/null; then
  interreflected=(bake glossy.glb --glossy --order 3 --samples 16 --bounces 1 -o full.prtg)
  full_disk 4 "a scratch file in .: No space left on device" glossy.glb "${interreflected[@]}"
  full_disk 14 "a scratch file in .: No space left on device" glossy.glb "${interreflected[@]}" \
    --bounce-precision f16
  full_disk 14 "No space left on device" full.prtg "${interreflected[@]}"
else
  echo "skipped: full-disk checks (no private mount namespace with a tmpfs here)"
fi

status=0
"$prt" bake glossy.glb -o small.prt --memory-limit 8Q --quiet >/dev/null 2>err.txt || status=$?
[[ $status == 2 ]] || fail "bake --memory-limit 8Q: exit status $status, expected 2"
expect_refusal "bake --memory-limit 8Q" 2 "--memory-limit" "not a memory size"

if ((failures)); then
  echo "$failures failure(s)"
  exit 1
fi
echo "every failed write left nothing behind"
