#!/usr/bin/env bash
# Frame time and first-frame time of `prt view` in headless Chromium (software WebGL), on the
# bake benchmark's field scene (`prt make-scene --scene field --vertices N`), baked at the given
# order. Prints measure_viewer.mjs's JSON line. Needs chromium, node and tests/viewer's npm
# packages (scripts/install-deps.sh --for test); exits 77 without them.
# Usage: measure_viewer.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR VERTICES ORDER FRAMES [WEB_DIR]
#   docs/BENCHMARKS.md: VERTICES=1000000 ORDER=4 FRAMES=20; ctest runs 20000 2 3.
set -euo pipefail
prt="$1" root="$2" out="$3" vertices="$4" order="$5" frames="$6" web="${7:-}"
[ -z "$web" ] || [ -f "$web/index.html" ] || { echo "skipping: the viewer's page was not built ($web)"; exit 77; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "skipping: chromium is not installed"; exit 77; }
command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed"; exit 77; }
[ -d "$root/tests/viewer/node_modules/puppeteer-core" ] || { echo "skipping: puppeteer-core is missing"; exit 77; }
mkdir -p "$out"
scene="$out/field_$vertices.glb" transfer="$out/field_${vertices}_o$order.prt"
[ -f "$scene" ] || "$prt" make-scene --scene field --vertices "$vertices" -o "$scene" >/dev/null
[ -f "$transfer" ] || "$prt" bake "$scene" -o "$transfer" --order "$order" --samples 16 --quiet
"$prt" view "$scene" "$transfer" "$root/data/sky.hdr" --port 0 --quiet >"$out/view.out" 2>"$out/view.err" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
url=""
for _ in $(seq 1 3000); do
  url="$(grep -o 'http://[^ ]*' "$out/view.out" || true)"
  [ -n "$url" ] && break
  kill -0 $server 2>/dev/null || { cat "$out/view.err"; exit 1; }
  sleep 0.1
done
node "$root/bench/viewer/measure_viewer.mjs" "$url" "$frames" "$root"
