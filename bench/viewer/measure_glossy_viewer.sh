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
. "$root/tests/viewer/view_server.sh"
require_browser "$root" "$web"
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
for file in "$name.prtq" "$name.prtg"; do
  start_view "$out" "$scene" "$out/$file" "$root/data/sky.hdr" --quiet
  node "$root/bench/viewer/measure_glossy_viewer.mjs" "$url" "$frames" "$root"
  stop_view
done
