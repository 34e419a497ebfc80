#!/usr/bin/env bash
# ctest driver of check_glossy_js.mjs: bakes `prt make-scene --scene glossy` (its four materials:
# Lambert, two isotropic glTF lobes read from tables, an anisotropic one from its view-side
# matrix) glossy at order 4 (grey, shadowed) and order 3 with a bounce (RGB transfer), compresses
# the first with CPCA, fetches each file's payloads from `prt view`, and compares web/glossy.js's
# per-vertex radiance with `prt relight --csv --eye` (window none, the light turned); and that
# bad glossy input is refused in one line. web/*.js
# are copied beside a link to tests/viewer/node_modules so that `import 'three'` resolves.
# Exits 77 (skipped) when node, three.js or the page's build is missing.
# Usage: run_glossy_js_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
here="$root/tests/viewer"
command -v node >/dev/null 2>&1 || { echo "skipping: node is not installed"; exit 77; }
[ -d "$here/node_modules/three" ] || { echo "skipping: $here/node_modules/three is missing (scripts/install-deps.sh --for test)"; exit 77; }
[ -f "$web/index.html" ] || { echo "skipping: the viewer's page was not built ($web/index.html)"; exit 77; }
. "$here/view_server.sh"
rm -rf "$out" && mkdir -p "$out/web"
cp "$root"/web/*.js "$out/web/"
ln -s "$here/node_modules" "$out/node_modules"
cp "$here/check_glossy_js.mjs" "$out/"
sky="$root/data/sky.hdr" scene="$out/glossy.glb"
"$prt" make-scene --scene glossy -o "$scene" >/dev/null
"$prt" bake "$scene" --glossy -o "$out/g4.prtg" --order 4 --samples 32 --quiet
"$prt" compress "$out/g4.prtg" -o "$out/g4.prtq" --clusters 8 --vectors 4 --quiet
"$prt" bake "$scene" --glossy -o "$out/g3rgb.prtg" --order 3 --samples 16 --bounces 1 --quiet
# Bad glossy input: one line naming the file, status 1, no URL (nothing served).
head -c 1000 "$out/g4.prtg" >"$out/truncated.prtg"
: >"$out/none.prte"
refuse() {  # refuse WHAT FILE ARGS...
  local what="$1" file="$2"; shift 2
  local status=0
  "$prt" view "$@" --port 0 >"$out/refused.out" 2>"$out/refused.err" || status=$?
  if [ "$status" != 1 ] || [ "$(wc -l <"$out/refused.err")" != 1 ] || ! grep -q "$file" "$out/refused.err" || [ -s "$out/refused.out" ]; then
    echo "FAIL $what: status $status, stderr: $(cat "$out/refused.err"), stdout: $(cat "$out/refused.out")"; exit 1
  fi
  echo "ok   $what: $(cat "$out/refused.err")"
}
refuse "a truncated .prtg" truncated.prtg "$scene" "$out/truncated.prtg" "$sky"
refuse "a .prtq of another scene" g4.prtq "$root/data/demo.glb" "$out/g4.prtq" "$sky"
refuse "emitters with a glossy file" g4.prtg "$scene" "$out/g4.prtg" "$sky" --emitters "$out/none.prte"
eye="-1.5,2.2,3.4" rotate="40,10,0"
for file in g4.prtg g4.prtq g3rgb.prtg; do
  dir="$out/${file/./_}" && mkdir -p "$dir"
  start_view "$dir" "$scene" "$out/$file" "$sky" --quiet
  for name in manifest.json mesh.bin transfer.bin glossy.bin; do curl -sf "${url}api/$name" -o "$dir/$name"; done
  stop_view
  "$prt" relight "$scene" "$out/$file" "$sky" -o "$dir/tiny.png" --size 32x18 --spp 1 --window none \
    --rotate "$rotate" --csv "$dir/vertices.csv" --eye "$eye" --quiet
  node "$out/check_glossy_js.mjs" "$dir" "$dir/vertices.csv" "$eye" "$rotate" "$out/web"
done
