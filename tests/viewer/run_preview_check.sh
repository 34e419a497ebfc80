#!/usr/bin/env bash
# ctest driver of check_preview.mjs: a field scene of 250k vertices (above the preview's
# threshold, cli/view/view_preview.h), baked briefly, served by `prt view --port 0`. Exits 77
# (skipped) with a message when chromium, node, the npm packages or the page's build are missing.
# Usage: run_preview_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
here="$root/tests/viewer"
. "$here/view_server.sh"
require_browser "$root" "$web"
rm -rf "$out" && mkdir -p "$out"
"$prt" make-scene --scene field --vertices 250000 -o "$out/field.glb" >/dev/null
"$prt" bake "$out/field.glb" -o "$out/field.prt" --order 3 --samples 4 --quiet
start_view "$out" "$out/field.glb" "$out/field.prt" "$root/data/sky.hdr" --quiet
node "$here/check_preview.mjs" "$url" "$out"
