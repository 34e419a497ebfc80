#!/usr/bin/env bash
# ctest driver of the real-browser test (check_browser.mjs): bakes the bundled demo, renders it
# with `prt relight` at the settings the page is given, starts `prt view --port 0`, and lets
# headless Chromium compare. Exits 77 (skipped) with a message when chromium, node, the npm
# packages or the page's build are missing (scripts/install-deps.sh --for test installs them).
# Usage: run_browser_check.sh PRT_BINARY REPOSITORY_ROOT SCRATCH_DIR WEB_DIR
set -euo pipefail
prt="$1" root="$2" out="$3" web="$4"
here="$root/tests/viewer"
. "$here/view_server.sh"
require_browser "$root" "$web"
rm -rf "$out" && mkdir -p "$out/room"
scene="$root/data/demo.glb" sky="$root/data/sky.hdr"
serve() {  # serve DIR ARGS...: prt view (view_server.sh), its manifest in DIR, FILE's exposure
  local dir="$1"; shift
  start_view "$dir" "$@" --quiet
  curl -sf "${url}api/manifest.json" -o "$dir/manifest.json"
  exposure="$(node -p "require('$dir/manifest.json').exposure_ev")"
}

# The demo: defaults and a rotation.
"$prt" bake "$scene" -o "$out/demo.prt" --order 4 --samples 64 --transfer interreflected \
  --ao --bent-normals --quiet
serve "$out" "$scene" "$out/demo.prt" "$sky"
relight() { "$prt" relight "$scene" "$out/demo.prt" "$sky" --size 640x360 --quiet "$@"; }
relight -o "$out/cpu_default.png"
relight -o "$out/cpu_r0.png" --exposure "$exposure" --window none --rotate 0,0,0
relight -o "$out/cpu_r90.png" --exposure "$exposure" --window none --rotate 90,0,0
node "$here/check_browser.mjs" "$url" "$out"
stop_view

# Two transfer kinds of the demo in one page (prt view --also): shadowed as FILE, interreflected
# as the extra display mode=also0, each against prt relight of its file at FILE's exposure.
also="$out/also" && mkdir -p "$also"
for kind in shadowed interreflected; do
  "$prt" bake "$scene" -o "$also/$kind.prt" --order 4 --samples 16 --transfer "$kind" --quiet
done
serve "$also" "$scene" "$also/shadowed.prt" "$sky" --also "$also/interreflected.prt"
for kind in shadowed interreflected; do
  "$prt" relight "$scene" "$also/$kind.prt" "$sky" --size 640x360 --quiet -o "$also/cpu_$kind.png" \
    --exposure "$exposure" --window none --rotate 30,0,0
done
node "$here/check_browser.mjs" "$url" "$also" also
stop_view

# A room lit by its lamps (tests/scripts/fixtures/room.obj): emitter responses on the bake's
# vertices (--max-edge), added to the sky's light as prt relight --emitters adds them; its
# interreflected bake as an --also display, the emitters added to it too, after the page's
# sliders have been moved (check_browser.mjs, SLIDERS: lamp ×0.5 of its emission 5,5,5; panel ×3
# of its 0.5,1,2, tinted to linear (1,0,0)).
room="$out/room"
cp "$root/tests/scripts/fixtures/room.obj" "$root/tests/scripts/fixtures/room.mtl" "$room/"
"$prt" radiosity "$room/room.obj" --max-edge 0.25 --per-emitter "$room/room.prte" --quiet
"$prt" bake "$room/room.obj" --max-edge 0.25 -o "$room/room.prt" --order 3 --samples 16 --quiet
"$prt" bake "$room/room.obj" --max-edge 0.25 -o "$room/room_ir.prt" --order 3 --samples 16 \
  --transfer interreflected --quiet
serve "$room" "$room/room.obj" "$room/room.prt" "$sky" --emitters "$room/room.prte" --max-edge 0.25 \
  --also "$room/room_ir.prt"
lit() { "$prt" relight "$room/room.obj" "$@" "$sky" --max-edge 0.25 --emitters "$room/room.prte" \
  --size 640x360 --spp 1 --quiet --exposure "$exposure" --window none; }
lit "$room/room.prt" -o "$room/cpu_emitters.png"
lit "$room/room.prt" -o "$room/cpu_lamp.png" --emitter lamp=2,1,0.5
lit "$room/room_ir.prt" -o "$room/cpu_emitters_interreflected.png"
sliders=(--emitter lamp=2.5,2.5,2.5 --emitter panel=1.5,0,0)
lit "$room/room.prt" -o "$room/cpu_sliders_shadowed.png" "${sliders[@]}"
lit "$room/room_ir.prt" -o "$room/cpu_sliders_interreflected.png" "${sliders[@]}"
node "$here/check_browser.mjs" "$url" "$room" emitters
stop_view

# Glossy files (`prt make-scene --scene glossy`, baked at order 4, and its CPCA compression):
# view-dependent shading at two cameras, camera B orbited 50° about the vertical through the
# target (check_browser.mjs, checkGlossy). 1024 rays a vertex (a few seconds): the .prtq's
# screenshot with the panel is the README's docs/images/viewer_glossy.png, and at 32 or 256 the
# Monte Carlo noise of the matrices shows as blotches on the floor, the sphere and the cube.
glossy="$out/glossy" && mkdir -p "$glossy"
"$prt" make-scene --scene glossy -o "$glossy/glossy.glb" >/dev/null
"$prt" bake "$glossy/glossy.glb" --glossy -o "$glossy/g.prtg" --order 4 --samples 1024 --quiet
"$prt" compress "$glossy/g.prtg" -o "$glossy/g.prtq" --clusters 8 --vectors 4 --quiet
for file in g.prtg g.prtq; do
  dir="$glossy/${file/./_}" && mkdir -p "$dir"
  serve "$dir" "$glossy/glossy.glb" "$glossy/$file" "$sky"
  cameras="$(node -e "
    const c = require('$dir/manifest.json').camera, t = c.target, a = 50 * Math.PI / 180;
    const d = [c.eye[0] - t[0], c.eye[2] - t[2]];
    const b = [t[0] + Math.cos(a) * d[0] + Math.sin(a) * d[1], c.eye[1], t[2] - Math.sin(a) * d[0] + Math.cos(a) * d[1]];
    const s = (e) => [...e, ...t, ...c.up, c.yfov_degrees].map((x) => +x.toFixed(6)).join(',');
    console.log(s(c.eye), s(b));")"
  read -r camera_a camera_b <<<"$cameras"
  shade() { "$prt" relight "$glossy/glossy.glb" "$glossy/$file" "$sky" --size 640x360 --quiet "$@"; }
  shade -o "$dir/cpu_default.png"
  shade -o "$dir/cpu_a.png" --camera "$camera_a" --exposure "$exposure" --window none --rotate 30,0,0
  shade -o "$dir/cpu_b.png" --camera "$camera_b" --exposure "$exposure" --window none --rotate 30,0,0
  node "$here/check_browser.mjs" "$url" "$dir" glossy "$camera_a" "$camera_b"
  stop_view
done
# A Haar-wavelet bake of the demo (cube 16, shadowed; check_browser_haar.mjs): the page computes
# the lighting of each rotation and the per-vertex sums in JavaScript, as prt relight does.
haar="$out/haar" && mkdir -p "$haar"
"$prt" bake "$scene" -o "$haar/demo_haar.prt" --basis haar --cube 16 --quiet
serve "$haar" "$scene" "$haar/demo_haar.prt" "$sky"
wavelets() { "$prt" relight "$scene" "$haar/demo_haar.prt" "$sky" --size 640x360 --quiet "$@"; }
wavelets -o "$haar/cpu_default.png"
wavelets -o "$haar/cpu_r0.png" --exposure "$exposure" --rotate 0,0,0
wavelets -o "$haar/cpu_r90.png" --exposure "$exposure" --rotate 90,0,0
wavelets -o "$haar/cpu_r90_k8.png" --exposure "$exposure" --rotate 90,0,0 --terms 8
node "$here/check_browser_haar.mjs" "$url" "$haar"
stop_view
# Options of SH files only are refused in one line, before any port is opened.
if "$prt" view "$scene" "$haar/demo_haar.prt" --max-edge 0.5 --port 0 2>"$haar/refused.err"; then
  echo "prt view accepted --max-edge with a Haar file"; exit 1
fi
grep -q "demo_haar.prt: holds Haar wavelets; --max-edge applies to SH files" "$haar/refused.err" ||
  { echo "unexpected refusal: $(cat "$haar/refused.err")"; exit 1; }
