#!/usr/bin/env bash
# Frame time of `prt view` on glossy files in headless Chromium (software WebGL): bakes SCENE
# glossy at ORDER (SAMPLES rays a vertex, MATERIAL as prt bake --material, "-" for the scene's
# own), compresses it by CPCA (CLUSTERS, VECTORS), and prints measure_glossy_viewer.mjs's JSON
# line for the .prtq and then for the .prtg. Needs chromium, node and tests/viewer's npm
# packages (scripts/install-deps.sh --for test); exits 77 without them.
# SCENE "glossy" is `prt make-scene --scene glossy`; any other value is a scene file.
# Usage: measure_glossy_viewer.sh PRT ROOT SCRATCH SCENE ORDER SAMPLES MATERIAL CLUSTERS VECTORS FRAMES [WEB_DIR]
#   docs/BENCHMARKS.md: the Stanford dragon at order 5; ctest runs the glossy scene at order 3.
set -euo pipefail
prt="$1" root="$2" out="$3" scene="$4" order="$5" samples="$6" material="$7" clusters="$8" vectors="$9"
frames="${10}" web="${11:-}"
[ -z "$web" ] || [ -f "$web/index.html" ] || { echo "skipping: the viewer's page was not built ($web)"; exit 77; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || { echo "skipping: chromium is not installed"; exit 77; }
command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed"; exit 77; }
[ -d "$root/tests/viewer/node_modules/puppeteer-core" ] || { echo "skipping: puppeteer-core is missing"; exit 77; }
mkdir -p "$out"
if [ "$scene" = glossy ]; then
  scene="$out/glossy.glb"
  "$prt" make-scene --scene glossy -o "$scene" >/dev/null
fi
[ -f "$scene" ] || { echo "skipping: $scene is missing"; exit 77; }
name="$(basename "${scene%.*}")_o$order"
options=()
[ "$material" = - ] || options=(--material "$material")
[ -f "$out/$name.prtg" ] || "$prt" bake "$scene" --glossy -o "$out/$name.prtg" --order "$order" \
  --samples "$samples" "${options[@]}" --quiet
[ -f "$out/$name.prtq" ] || "$prt" compress "$out/$name.prtg" -o "$out/$name.prtq" \
  --clusters "$clusters" --vectors "$vectors" --quiet
server=""
trap '[ -z "$server" ] || kill $server 2>/dev/null || true' EXIT
for file in "$name.prtq" "$name.prtg"; do
  "$prt" view "$scene" "$out/$file" "$root/data/sky.hdr" --port 0 --quiet >"$out/view.out" 2>"$out/view.err" &
  server=$!
  url=""
  for _ in $(seq 1 3000); do
    url="$(grep -so 'http://[^ ]*' "$out/view.out" || true)"
    [ -n "$url" ] && break
    kill -0 $server 2>/dev/null || { cat "$out/view.err"; exit 1; }
    sleep 0.1
  done
  node "$root/bench/viewer/measure_glossy_viewer.mjs" "$url" "$frames" "$root"
  kill $server && wait $server 2>/dev/null || true
  server=""
done
