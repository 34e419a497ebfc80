#!/usr/bin/env bash
# Frame time and first-frame time of `prt view` in headless Chromium (software WebGL), on the
# bake benchmark's field scene (`prt make-scene --scene field --vertices N`), baked at the given
# order. Prints measure_viewer.mjs's JSON line. Needs chromium, node and tests/viewer's npm
# packages (scripts/install-deps.sh --for test); exits 77 without them.
# Usage: measure_viewer.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR VERTICES ORDER FRAMES [WEB_DIR]
#   docs/BENCHMARKS.md: VERTICES=1000000 ORDER=4 FRAMES=20; ctest runs 20000 2 3.
set -euo pipefail
prt="$1" root="$2" out="$3" vertices="$4" order="$5" frames="$6" web="${7:-}"
. "$root/tests/viewer/view_server.sh"
require_browser "$root" "$web"
mkdir -p "$out"
scene="$out/field_$vertices.glb" transfer="$out/field_${vertices}_o$order.prt"
[ -f "$scene" ] || "$prt" make-scene --scene field --vertices "$vertices" -o "$scene" >/dev/null
[ -f "$transfer" ] || "$prt" bake "$scene" -o "$transfer" --order "$order" --samples 16 --quiet
start_view "$out" "$scene" "$transfer" "$root/data/sky.hdr" --quiet
node "$root/bench/viewer/measure_viewer.mjs" "$url" "$frames" "$root"
