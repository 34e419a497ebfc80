#!/usr/bin/env bash
# ctest driver: `prt relight --vertex-colors` on the bundled scene, then the GLB loaded with
# three.js's GLTFLoader under Node (check_unlit_glb.mjs), plain and tone-mapped.
# Usage: run_viewer_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR
# Exits 77 (ctest: skipped) with a message when node or the pinned three package is missing;
# scripts/install-deps.sh --for test installs both. Nothing is downloaded here.
set -euo pipefail
prt="$1" root="$2" out="$3"
here="$root/tests/viewer"
if ! command -v node >/dev/null 2>&1; then
  echo "skipping: node is not installed (bash scripts/install-deps.sh --for test installs it)"
  exit 77
fi
if [ ! -f "$here/node_modules/three/examples/jsm/loaders/GLTFLoader.js" ]; then
  echo "skipping: $here/node_modules/three is missing (bash scripts/install-deps.sh --for test installs it)"
  exit 77
fi
rm -rf "$out" && mkdir -p "$out"
"$prt" bake "$root/data/demo.glb" -o "$out/demo.prt" --order 3 --samples 16 --quiet
"$prt" relight "$root/data/demo.glb" "$out/demo.prt" "$root/data/sky.hdr" -o "$out/demo.png" \
  --size 64x36 --spp 1 --csv "$out/demo.csv" --vertex-colors "$out/linear.glb" --quiet
node "$here/check_unlit_glb.mjs" "$out/linear.glb" "$out/demo.csv"
"$prt" relight "$root/data/demo.glb" "$out/demo.prt" "$root/data/sky.hdr" -o "$out/demo.png" \
  --size 64x36 --spp 1 --exposure -1.5 --vertex-colors "$out/tonemapped.glb" \
  --vertex-colors-tonemap --quiet
node "$here/check_unlit_glb.mjs" "$out/tonemapped.glb" "$out/demo.csv" --tonemap -1.5
