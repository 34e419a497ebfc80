#!/usr/bin/env bash
# Time per light change of `prt view` on a Haar-wavelet file, in headless Chromium: starts
# `prt view SCENE FILE ENV`, lets measure_haar_view.mjs turn the light CHANGES times and prints
# its JSON line (median times of the rotated cube, the Haar transform, the selection, the sparse
# sum, and the frame). Needs chromium, node and tests/viewer's npm packages
# (scripts/install-deps.sh --for test); exits 77 without them.
# Usage: measure_haar_view.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR SCENE FILE ENV CHANGES [TERMS]
set -euo pipefail
prt="$1" root="$2" out="$3" scene="$4" transfer="$5" env="$6" changes="$7" terms="${8:-200}"
. "$root/tests/viewer/view_server.sh"
require_browser "$root"
mkdir -p "$out"
start=$(date +%s.%N)
start_view "$out" "$scene" "$transfer" "$env"
echo "prt view started in $(echo "$(date +%s.%N) - $start" | bc) s: $(head -1 "$out/view.out")"
node "$root/bench/viewer/measure_haar_view.mjs" "$url" "$changes" "$terms" "$root" "$out"
