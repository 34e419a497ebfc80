#!/usr/bin/env bash
# ctest driver of check_export_gltf.mjs: bakes the bundled demo (with AO and bent normals),
# exports it with `prt export-gltf` and the bundled sky, writes `prt relight --csv` of the same
# file and sky (--window none), and lets node compare. web/*.js are copied beside a link to
# tests/viewer/node_modules so that their `import 'three'` resolves under node as in a browser's
# import map. Exits 77 (skipped) when node or three.js is missing.
# Usage: run_export_gltf_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR
set -euo pipefail
prt="$1" root="$2" out="$3"
here="$root/tests/viewer"
command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed (scripts/install-deps.sh --for test)"; exit 77; }
[ -d "$here/node_modules/three" ] || { echo "skipping: $here/node_modules/three is missing (scripts/install-deps.sh --for test)"; exit 77; }
rm -rf "$out" && mkdir -p "$out/web"
cp "$root"/web/*.js "$out/web/"
ln -s "$here/node_modules" "$out/node_modules"
for order in 3 8; do
  "$prt" bake "$root/data/demo.glb" -o "$out/demo$order.prt" --order $order --samples 32 --ao --bent-normals --quiet
  "$prt" export-gltf "$root/data/demo.glb" "$out/demo$order.prt" "$root/data/sky.hdr" -o "$out/demo$order.glb" --quiet
  "$prt" relight "$root/data/demo.glb" "$out/demo$order.prt" "$root/data/sky.hdr" -o "$out/demo$order.png" \
    --size 32x18 --spp 1 --window none --csv "$out/demo$order.csv" --quiet
  cp "$here/check_export_gltf.mjs" "$out/"
  node "$out/check_export_gltf.mjs" "$out/demo$order.glb" "$out/demo$order.csv" "$out/web" --expect-ao
done
