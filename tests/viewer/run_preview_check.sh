#!/usr/bin/env bash
# ctest driver of check_preview.mjs: a field scene of 250k vertices (above the preview's
# threshold, cli/view/view_preview.h), baked briefly, served by `prt view --port 0`. Exits 77
# (skipped) with a message when chromium, node, the npm packages or the page's build are missing.
# Usage: run_preview_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
here="$root/tests/viewer"
skip() { echo "skipping: $1 (bash scripts/install-deps.sh --for test installs it)"; exit 77; }
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || skip "chromium is not installed"
command -v node >/dev/null 2>&1 || skip "node is not installed"
[ -d "$here/node_modules/puppeteer-core" ] || skip "$here/node_modules/puppeteer-core is missing"
[ -f "$web/index.html" ] || skip "the viewer's page was not built ($web/index.html)"
rm -rf "$out" && mkdir -p "$out"
"$prt" make-scene --scene field --vertices 250000 -o "$out/field.glb" >/dev/null
"$prt" bake "$out/field.glb" -o "$out/field.prt" --order 3 --samples 4 --quiet
"$prt" view "$out/field.glb" "$out/field.prt" "$root/data/sky.hdr" --port 0 --quiet >"$out/view.out" 2>"$out/view.err" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
url=""
for _ in $(seq 1 1200); do
  url="$(grep -o 'http://[^ ]*' "$out/view.out" || true)"
  [ -n "$url" ] && break
  kill -0 $server 2>/dev/null || { cat "$out/view.err"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { echo "prt view printed no URL"; exit 1; }
node "$here/check_preview.mjs" "$url" "$out"
