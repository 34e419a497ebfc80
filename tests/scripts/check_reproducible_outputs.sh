#!/usr/bin/env bash
# Every file kind prt writes is the same, byte for byte, whether it was made with one thread or
# two: SH bakes (shadowed with AO and bent normals, interreflected with f32 and f16 bounces,
# interreflected with a texture kept apart, --auto with and without --env, obscurance,
# --subsurface, the parts of --shard and their merge, with --subsurface too), Haar (shadowed,
# interreflected textured), glossy shadowed and interreflected (.prtg), CPCA (.prtq), radiosity
# (.prte with --per-emitter, the form-factor cache, --csv, --vertex-colors .glb, the EXR image;
# Gauss-Seidel, Jacobi, progressive, --adaptive; the hierarchical link cache), export-gltf,
# make-scene (the demo and the translucent scene) and
# make-sky.
# Nothing that changes from run to run (wall times, thread counts, the host) may be in them: that
# goes to the OUT.run.json beside each output, which is checked to exist and is not compared.
# Each pair is made in its own folder with the same relative paths, so a path recorded as given
# is the same in both. Small settings: about 20 s on the shared 2-core machine.
# Usage: check_reproducible_outputs.sh PRT_BINARY SOURCE_DIR
# The shadowed AO bake is checked with obscurance (--ao-distance) too.
set -euo pipefail
prt="$(realpath "$1")"
source_dir="$(realpath "$2")"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
failures=0

# Inputs shared by both runs, in scratch/in (relative paths from each run folder: ../in/...).
mkdir -p "$scratch/in" "$scratch/t1" "$scratch/t2"
cd "$scratch/in"
cp "$source_dir/data/demo.glb" "$source_dir/data/sky.hdr" .
"$prt" make-scene --scene glossy -o glossy.glb >/dev/null
python3 "$source_dir/scripts/textured-example.py" tex >/dev/null
# A unit room open at the front, a lamp and a panel (two emitting materials).
cp "$source_dir"/tests/scripts/fixtures/room.{obj,mtl} .

# Runs `prt ARGS... --threads N` in scratch/tN for N = 1, 2 (make-scene has no --threads:
# the first argument says whether to pass it).
both() {  # threads(yes|no) args...
  local pass_threads="$1"; shift
  for n in 1 2; do
    local extra=()
    [[ "$pass_threads" == yes ]] && extra=(--threads "$n")
    (cd "$scratch/t$n" && "$prt" "$@" "${extra[@]}" >/dev/null) ||
      { echo "FAIL: prt $* --threads $n exited with status $?"; failures=$((failures + 1)); }
  done
}

# Compares scratch/t1/FILE with scratch/t2/FILE and checks that FILE.run.json exists.
same() {  # label file [run-record: yes|no]
  local label="$1" file="$2" record="${3:-yes}"
  if [[ ! -f "$scratch/t1/$file" || ! -f "$scratch/t2/$file" ]]; then
    echo "FAIL: $label: $file was not written"; failures=$((failures + 1)); return
  fi
  if cmp -s "$scratch/t1/$file" "$scratch/t2/$file"; then
    echo "ok: $label ($file, $(stat -c %s "$scratch/t1/$file") bytes)"
  else
    echo "FAIL: $label: $file differs between --threads 1 and --threads 2" \
      "($(cmp "$scratch/t1/$file" "$scratch/t2/$file" 2>&1 | head -1))"
    failures=$((failures + 1))
  fi
  if [[ "$record" == yes && ! -f "$scratch/t1/$file.run.json" ]]; then
    echo "FAIL: $label: $file.run.json (the run's times and threads) was not written"
    failures=$((failures + 1))
  fi
}

demo=../in/demo.glb glossy=../in/glossy.glb tex=../in/tex/corner.gltf room=../in/room.obj
both yes bake --quiet "$demo" -o shadowed.prt --order 3 --samples 32 --ao --bent-normals --seed 3
same "shadowed, --ao --bent-normals" shadowed.prt
both yes bake --quiet "$demo" -o obscurance.prt --order 2 --samples 32 --ao --bent-normals \
  --ao-distance 0.3 --ao-falloff smoothstep
same "shadowed, obscurance (--ao-distance)" obscurance.prt
both yes bake --quiet "$demo" -o interreflected.prt --transfer interreflected --order 3 --samples 16
same "interreflected" interreflected.prt
both yes bake --quiet "$demo" -o interreflected_f16.prt --transfer interreflected --order 3 \
  --samples 16 --bounce-precision f16
same "interreflected, --bounce-precision f16" interreflected_f16.prt
both yes bake --quiet "$demo" -o subsurface.prt --transfer interreflected --order 3 --samples 16 \
  --subsurface marble
same "interreflected, --subsurface marble" subsurface.prt
for i in 0 1; do
  both yes bake --quiet "$demo" -o "shard$i.prtpart" --transfer interreflected --order 3 \
    --samples 16 --shard "$i/2"
  same "interreflected, --shard $i/2 (part)" "shard$i.prtpart"
done
both yes merge --quiet shard1.prtpart shard0.prtpart -o merged.prt
same "merge of the interreflected parts" merged.prt
cmp -s "$scratch/t1/merged.prt" "$scratch/t1/interreflected.prt" ||
  { echo "FAIL: the merged parts differ from the single interreflected bake"; failures=$((failures + 1)); }
for i in 0 1; do
  both yes bake --quiet "$demo" -o "subsurface$i.prtpart" --transfer interreflected --order 3 \
    --samples 16 --subsurface marble --shard "$i/2"
  same "interreflected, --subsurface marble --shard $i/2 (part)" "subsurface$i.prtpart"
done
both yes merge --quiet subsurface1.prtpart subsurface0.prtpart -o subsurface-merged.prt
same "merge of the subsurface parts" subsurface-merged.prt
cmp -s "$scratch/t1/subsurface-merged.prt" "$scratch/t1/subsurface.prt" ||
  { echo "FAIL: the merged subsurface parts differ from the single subsurface bake"; failures=$((failures + 1)); }
both yes bake --quiet "$tex" -o textured.prt --transfer interreflected --order 2 --samples 16
same "interreflected, textured (albedo kept apart)" textured.prt
both yes bake --quiet "$demo" -o auto.prt --auto --tolerance 0.3
same "--auto" auto.prt
both yes bake --quiet "$demo" -o auto-env.prt --auto --tolerance 0.3 --env ../in/sky.hdr
same "--auto --env" auto-env.prt
both yes bake --quiet "$demo" -o haar.prt --basis haar --cube 8
same "Haar" haar.prt
for i in 0 1; do
  both yes bake --quiet "$demo" -o "haar$i.prtpart" --basis haar --cube 8 --shard "$i/2"
  same "Haar, --shard $i/2 (part)" "haar$i.prtpart"
done
both yes merge --quiet haar0.prtpart haar1.prtpart -o haar-merged.prt
cmp -s "$scratch/t1/haar-merged.prt" "$scratch/t1/haar.prt" && cmp -s "$scratch/t2/haar-merged.prt" \
  "$scratch/t1/haar.prt" ||
  { echo "FAIL: the merged Haar parts differ from the single Haar bake"; failures=$((failures + 1)); }
both yes bake --quiet "$tex" -o haar-ir.prt --basis haar --cube 8 --transfer interreflected
same "Haar interreflected, textured" haar-ir.prt
both yes bake --quiet "$glossy" --glossy -o glossy.prtg --order 2 --samples 16
same "glossy shadowed" glossy.prtg
both yes bake --quiet "$glossy" --glossy -o glossy-ir.prtg --order 2 --samples 16 --transfer \
  interreflected --bounces 1
same "glossy interreflected" glossy-ir.prtg
for i in 0 1; do
  both yes bake --quiet "$glossy" --glossy -o "glossy$i.prtpart" --order 2 --samples 16 \
    --transfer interreflected --bounces 1 --shard "$i/2"
  same "glossy interreflected, --shard $i/2 (part)" "glossy$i.prtpart"
done
both yes merge --quiet glossy1.prtpart glossy0.prtpart -o glossy-merged.prtg
cmp -s "$scratch/t1/glossy-merged.prtg" "$scratch/t1/glossy-ir.prtg" &&
  cmp -s "$scratch/t2/glossy-merged.prtg" "$scratch/t1/glossy-ir.prtg" ||
  { echo "FAIL: the merged glossy parts differ from the single glossy bake"; failures=$((failures + 1)); }
both yes compress --quiet glossy-ir.prtg -o glossy-ir.prtq --clusters 2 --vectors 2 --seed 5
same "CPCA compression" glossy-ir.prtq
both yes radiosity --quiet "$room" --max-edge 0.25 --form-factors rays --rays 64 --seed 5 \
  --per-emitter room.prte --csv room.csv --vertex-colors room.glb --form-factor-cache room.ffc \
  --size 16x12 -o room.exr
same "radiosity --per-emitter" room.prte
same "radiosity form-factor cache" room.ffc no
same "radiosity --csv" room.csv no
same "radiosity --vertex-colors" room.glb no
same "radiosity image (.exr)" room.exr no
both yes radiosity --quiet "$room" --max-edge 0.25 --form-factors hemicube --hemicube 8 \
  --solver jacobi --per-emitter hemicube.prte --size 16x12 -o hemicube.exr
same "radiosity hemicube, Jacobi" hemicube.prte
both yes radiosity --quiet "$room" --max-edge 0.25 --form-factors analytic --solver progressive \
  --csv progressive.csv
same "radiosity analytic, progressive" progressive.csv
both yes radiosity --quiet "$room" --max-edge 0.5 --adaptive 0.05 --max-patches 300 \
  --csv adaptive.csv
same "radiosity --adaptive" adaptive.csv
both yes radiosity --quiet "$room" --max-edge 0.25 --solver hierarchical \
  --form-factor-cache room.links --csv hierarchical.csv
same "radiosity hierarchical link cache" room.links no
both no export-gltf --quiet "$demo" shadowed.prt ../in/sky.hdr -o export.glb
same "export-gltf" export.glb no
both no make-scene -o scene.glb
same "make-scene" scene.glb no
both no make-scene --scene translucent -o translucent.glb
same "make-scene translucent" translucent.glb no
both no make-sky -o sky.hdr --width 64 --height 32
same "make-sky" sky.hdr no

if ((failures)); then
  echo "$failures output(s) depend on the thread count or the run"
  exit 1
fi
echo "every output is byte-identical for 1 and 2 threads"
