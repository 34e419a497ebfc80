#!/usr/bin/env bash
# scripts/glossy-scale-scene.py at a small size: the scene it writes loads, its counts are the
# ones it prints, and a streamed glossy bake of it (prt bake --glossy) is read back by prt info
# with every vertex. Usage: check_glossy_scale_scene.sh PRT SOURCE_DIR WORK_DIR
set -euo pipefail
prt=$1 src=$2 work=$3
command -v python3 >/dev/null || { echo "python3 missing: skipped"; exit 77; }
mkdir -p "$work"
out=$(python3 "$src/scripts/glossy-scale-scene.py" --ground-vertices 4900 --spheres 3 \
  --sphere-segments 16 -o "$work/scale.obj")
echo "$out"
# 70 x 70 ground + 3 spheres of 16 x 8 (2 poles + 7 rings of 16 = 114 vertices, 224 triangles).
[[ $out == *"5242 vertices, 10194 triangles"* ]] || { echo "unexpected counts: $out"; exit 1; }
"$prt" bake "$work/scale.obj" --glossy --order 3 --samples 16 --threads 2 --quiet \
  --material 'glossy0=ward:rho_d=0.2,rho_s=0.3,ax=0.2,ay=0.2' -o "$work/scale.prtg"
info=$("$prt" info "$work/scale.prtg")
echo "$info" | grep -q "^vertices *5242$" || { echo "prt info: $info"; exit 1; }
echo "$info" | grep -q "ward(rho_d 0.2, rho_s 0.3, alpha 0.2x0.2) *114 vertices" ||
  { echo "prt info: $info"; exit 1; }
ls "$work" | grep -q "tmp-" && { echo "a temporary file was left"; exit 1; }
echo "ok"
