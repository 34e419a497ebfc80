#!/usr/bin/env bash
# Time per light change of `prt view` on a Haar-wavelet file, in headless Chromium: starts
# `prt view SCENE FILE ENV`, lets measure_haar_view.mjs turn the light CHANGES times and prints
# its JSON line (median times of the rotated cube, the Haar transform, the selection, the sparse
# sum, and the frame). Needs chromium, node and tests/viewer's npm packages
# (scripts/install-deps.sh --for test); exits 77 without them.
# Usage: measure_haar_view.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR SCENE FILE ENV CHANGES [TERMS]
set -euo pipefail
prt="$1" root="$2" out="$3" scene="$4" transfer="$5" env="$6" changes="$7" terms="${8:-200}"
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "skipping: chromium is not installed"; exit 77; }
command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed"; exit 77; }
[ -d "$root/tests/viewer/node_modules/puppeteer-core" ] || { echo "skipping: puppeteer-core is missing"; exit 77; }
mkdir -p "$out"
start=$(date +%s.%N)
"$prt" view "$scene" "$transfer" "$env" --port 0 >"$out/view.out" 2>"$out/view.err" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
url=""
for _ in $(seq 1 6000); do
  url="$(grep -o 'http://[^ ]*' "$out/view.out" || true)"
  [ -n "$url" ] && break
  kill -0 $server 2>/dev/null || { cat "$out/view.err"; exit 1; }
  sleep 0.1
done
echo "prt view started in $(echo "$(date +%s.%N) - $start" | bc) s: $(head -1 "$out/view.out")"
node "$root/bench/viewer/measure_haar_view.mjs" "$url" "$changes" "$terms" "$root" "$out"
