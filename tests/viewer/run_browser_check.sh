#!/usr/bin/env bash
# ctest driver of the real-browser test (check_browser.mjs): bakes the bundled demo, renders it
# with `prt relight` at the settings the page is given, starts `prt view --port 0`, and lets
# headless Chromium compare. Exits 77 (skipped) with a message when chromium, node, the npm
# packages or the page's build are missing (scripts/install-deps.sh --for test installs them).
# Usage: run_browser_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
here="$root/tests/viewer"
chromium="${CHROMIUM:-/usr/bin/chromium}"
skip() { echo "skipping: $1 (bash scripts/install-deps.sh --for test installs it)"; exit 77; }
[ -x "$chromium" ] || skip "chromium is not installed"
command -v node >/dev/null 2>&1 || skip "node is not installed"
[ -d "$here/node_modules/puppeteer-core" ] || skip "$here/node_modules/puppeteer-core is missing"
[ -f "$web/index.html" ] || skip "the viewer's page was not built ($web/index.html)"
rm -rf "$out" && mkdir -p "$out"
scene="$root/data/demo.glb" sky="$root/data/sky.hdr"
"$prt" bake "$scene" -o "$out/demo.prt" --order 4 --samples 64 --transfer interreflected \
  --ao --bent-normals --quiet
"$prt" view "$scene" "$out/demo.prt" "$sky" --port 0 --quiet >"$out/view.out" 2>"$out/view.err" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
url=""
for _ in $(seq 1 300); do
  url="$(grep -o 'http://[^ ]*' "$out/view.out" || true)"
  [ -n "$url" ] && break
  kill -0 $server 2>/dev/null || { cat "$out/view.err"; exit 1; }
  sleep 0.1
done
[ -n "$url" ] || { echo "prt view printed no URL"; exit 1; }
curl -sf "${url}api/manifest.json" -o "$out/manifest.json"
exposure="$(node -p "require('$out/manifest.json').exposure_ev")"
relight() { "$prt" relight "$scene" "$out/demo.prt" "$sky" --size 640x360 --quiet "$@"; }
relight -o "$out/cpu_default.png"
relight -o "$out/cpu_r0.png" --exposure "$exposure" --window none --rotate 0,0,0
relight -o "$out/cpu_r90.png" --exposure "$exposure" --window none --rotate 90,0,0
node "$here/check_browser.mjs" "$url" "$out"
