#!/usr/bin/env bash
# Prints SHA-256 fingerprints (16 hex digits) of what prt computes, at fixed seeds and small
# settings, so that a refactor can show it changed nothing: run it on the binary before and
# after and compare the outputs. One line per output, a label then the hash. Two runs of the
# same binary print the same lines (checked: three runs, one of them pinned to one core, and
# from two checkout paths): the bakes and the compression are bit-identical for any thread
# count (checked with --threads 1 and 3), radiosity seeds each patch's rays by its index, and
# nothing hashed depends on wall time or on where the files are.
#
# * Coefficient files of every kind (.prt SH and Haar, .prtg glossy, .prtq CPCA, .prte emitter
#   responses), "content": the bytes of every section and of the header, except what changes
#   from run to run: the header's file size and checksum and the metadata's wall times
#   ("seconds*", "*_seconds") and thread count ("threads"), which are dropped from the JSON
#   before hashing (a .prtq's embedded source section likewise); .prte files hold no metadata
#   and are hashed whole. (prt now keeps those out of its files, in OUT.run.json beside them;
#   they are still dropped so that an older binary hashes alike.) SH files also by `prt info
#   --csv` (coefficients to 9 significant digits) and "metadata": `prt info --json` without
#   times, the run record ("run"), file name, size and SH convention.
#   Every path is relative to a scratch directory, since bake metadata records the scene's path
#   as it was given.
# * Relit vertex colours: `prt relight --csv`, glossy files toward a fixed --eye, emitter
#   responses recoloured with --emitter, emitters added to an SH relight.
# * Images: the pixel values of the EXR outputs (`iinfo --hash`, SHA-1 of the pixels; the
#   header is not prt's computation).
# * `prt radiosity --csv` for each form-factor method with Gauss-Seidel and Jacobi (with
#   --per-emitter), progressive refinement, independent ray sampling, adaptive subdivision and a
#   form-factor cache (the file, then reused with another emission); `prt env` (the JSON without
#   the convention text) and the generated data (`prt make-scene`, `prt make-sky`).
# The SH convention text is left out: every command prints it identically, and the tests compare
# it as such. About 25 s of CPU (under a minute on the shared 2-core machine). --quick runs every
# command with smaller settings (15 s of CPU, mostly fixed start-up and BRDF-projection costs)
# and prints the same labels, for the test that keeps this script working; its hashes are not
# the reference ones.
# Usage: scripts/behaviour-hashes.sh [--quick] [PRT_BINARY] > hashes.txt
set -euo pipefail
quick=0
if [[ "${1:-}" == --quick ]]; then quick=1; shift; fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prt="$(realpath "${1:-$root/build/bin/prt}")"
[[ -x "$prt" ]] || { echo "behaviour-hashes.sh: $prt: not an executable" >&2; exit 1; }
command -v iinfo >/dev/null ||
  { echo "behaviour-hashes.sh: iinfo (openimageio-tools) is missing" >&2; exit 1; }
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cp "$root/data/demo.glb" "$root/data/sky.hdr" "$scratch/"
cd "$scratch"
scene=demo.glb
sky=sky.hdr

if ((quick)); then
  shadowed=(--order 3 --samples 32) interreflected=(--order 2 --samples 16) tolerance=0.3
  size=32x24 glossy_settings=(--order 2 --samples 16) cpca=(--clusters 2 --vectors 2)
  edge=0.5 rays=32 emitter_rays=256 hemicube=8 max_patches=100 sky_size=(--width 64 --height 32)
else
  shadowed=(--order 5 --samples 256) interreflected=(--order 4 --samples 128) tolerance=0.1
  size=96x64 glossy_settings=(--order 3 --samples 32) cpca=(--clusters 8 --vectors 4)
  edge=0.25 rays=256 emitter_rays=4096 hemicube=32 max_patches=400 sky_size=()
fi

# Each output is recorded here (label, how to hash it, file) and hashed at the end, in order:
# one iinfo and one python for all of them (each costs a start-up of about 0.3 s).
record() { printf '%s\t%s\t%s\n' "$1" "$2" "$3" >> manifest.tsv; }
hash_file() { record "$1" file "$2"; }
hash_content() { record "$1" content "$2"; }
hash_image() { record "$1" image "$2"; }
hash_metadata() {  # label, coefficient file
  "$prt" info "$2" --json > "$2.info.json"
  record "$1" metadata "$2.info.json"
}

# ---- Diffuse SH, adaptive and Haar bakes of the demo scene -------------------------------------
sh_bake() {  # name, extra bake arguments
  local name="$1"; shift
  "$prt" bake "$scene" -o "$name.prt" --quiet --seed 7 "$@"
  "$prt" info "$name.prt" --csv > "$name.info.csv"
  hash_file "$name coefficients" "$name.info.csv"
  hash_metadata "$name metadata" "$name.prt"
  hash_content "$name content" "$name.prt"
  "$prt" relight "$scene" "$name.prt" "$sky" -o "$name.exr" --size "$size" --csv "$name.csv" \
    >/dev/null 2>&1
  hash_file "$name relit" "$name.csv"
  hash_image "$name image" "$name.exr"
}

sh_bake shadowed --transfer shadowed "${shadowed[@]}" --ao --bent-normals
sh_bake interreflected --transfer interreflected "${interreflected[@]}"
sh_bake auto --auto --env "$sky" --tolerance "$tolerance"
"$prt" bake "$scene" -o haar.prt --quiet --seed 7 --basis haar --cube 8
hash_content "haar content" haar.prt
"$prt" relight "$scene" haar.prt "$sky" -o haar.exr --size "$size" --csv haar.csv >/dev/null 2>&1
hash_file "haar relit" haar.csv
hash_image "haar image" haar.exr
"$prt" env "$sky" --order 5 --json > env.json
record "env coefficients" env env.json

# ---- Generated data --------------------------------------------------------------------------------
"$prt" make-scene -o generated-demo.glb >/dev/null
hash_file "make-scene demo" generated-demo.glb
"$prt" make-scene --scene glossy -o glossy.glb >/dev/null
hash_file "make-scene glossy" glossy.glb
"$prt" make-sky -o generated-sky.hdr "${sky_size[@]}" >/dev/null
hash_file "make-sky" generated-sky.hdr

# ---- Glossy transfer (.prtg) and its CPCA compression (.prtq) of the glossy scene ---------------
glossy=glossy.glb
eye=0.4,1.9,4.2  # the scene's camera
glossy_relight() {  # label, file, extra relight arguments
  local label="$1" transfer="$2"; shift 2
  "$prt" relight "$glossy" "$transfer" "$sky" -o "$label.exr" --size "$size" --eye "$eye" \
    --csv "$label.csv" "$@" >/dev/null 2>&1
  hash_file "$label relit" "$label.csv"
  hash_image "$label image" "$label.exr"
}
glossy_bake() {  # name, extra bake arguments
  local name="$1"; shift
  "$prt" bake "$glossy" --glossy -o "$name.prtg" --quiet --seed 7 "${glossy_settings[@]}" "$@"
  hash_content "$name content" "$name.prtg"
  hash_metadata "$name metadata" "$name.prtg"
  glossy_relight "$name" "$name.prtg"
  "$prt" compress "$name.prtg" -o "$name.prtq" "${cpca[@]}" --seed 7 --quiet
  hash_content "$name-cpca content" "$name.prtq"
  glossy_relight "$name-cpca" "$name.prtq"
}
glossy_bake glossy-shadowed
glossy_bake glossy-interreflected --bounces 1
"$prt" compress glossy-shadowed.prtg -o matrix.prtq "${cpca[@]}" --seed 7 --metric matrix --quiet
hash_content "glossy-shadowed-cpca-matrix content" matrix.prtq
"$prt" relight "$glossy" glossy-shadowed.prtg "$sky" -o material.exr --size "$size" --eye "$eye" \
  --csv material.csv --material 'floor=ggx:alpha=0.3,f0=0.04,kd=0.3' >/dev/null 2>&1
hash_file "glossy-shadowed --material relit" material.csv

# ---- Radiosity: a room open at the front, a lamp and a panel (two emitting materials) ---------
cp "$root"/tests/scripts/fixtures/room.{obj,mtl} .
room=room.obj
radiosity() {  # label, extra radiosity arguments
  local label="$1"; shift
  "$prt" radiosity "$room" --max-edge "$edge" --size "$size" -o "$label.exr" \
    --csv "$label.csv" --quiet "$@" >/dev/null
  hash_file "$label csv" "$label.csv"
  hash_image "$label image" "$label.exr"
}
for method in analytic rays hemicube; do
  case $method in
    rays) options=(--form-factors rays --rays "$rays" --seed 7) ;;
    hemicube) options=(--form-factors hemicube --hemicube "$hemicube") ;;
    *) options=(--form-factors analytic) ;;
  esac
  for solver in gauss-seidel jacobi; do
    label="radiosity-$method-$solver"
    radiosity "$label" "${options[@]}" --solver "$solver" --per-emitter "$label.prte"
    hash_content "$label prte" "$label.prte"
    "$prt" relight "$label.prte" -o "$label-relit.exr" --size "$size" --emitter lamp=1,2,3 \
      --emitter panel=0.5 --csv "$label-relit.csv" --quiet >/dev/null
    hash_file "$label relit" "$label-relit.csv"
    hash_image "$label relit image" "$label-relit.exr"
  done
done
radiosity radiosity-analytic-progressive --solver progressive
radiosity radiosity-rays-independent --form-factors rays --rays "$rays" --seed 7 \
  --emitter-rays "$emitter_rays" --ray-sampling independent
radiosity radiosity-adaptive --adaptive 0.05 --max-patches "$max_patches"
radiosity radiosity-cache --form-factor-cache room.ffc
hash_file "radiosity-cache file" room.ffc
radiosity radiosity-cache-reused --form-factor-cache room.ffc --emission lamp=9,3,1

# Emitters added to environment lighting: PRT of the room's vertices plus the responses.
"$prt" bake "$room" -o room.prt --quiet --seed 7 --max-edge "$edge" --transfer interreflected \
  "${interreflected[@]}"
hash_content "room interreflected content" room.prt
"$prt" relight "$room" room.prt "$sky" --max-edge "$edge" -o sum.exr --size "$size" \
  --emitters radiosity-analytic-gauss-seidel.prte --emitter lamp=2 --csv sum.csv >/dev/null 2>&1
hash_file "room sky+emitters relit" sum.csv
hash_image "room sky+emitters image" sum.exr

# ---- The hashes, in the order recorded ----------------------------------------------------------
grep -P '\timage\t' manifest.tsv | cut -f3 | xargs iinfo --hash > images.txt
python3 - <<'EOF'
import hashlib, json, struct, sys

def digest(data):
    return hashlib.sha256(data).hexdigest()[:16]

def without(x, drop):
    if isinstance(x, dict):
        return {k: without(v, drop) for k, v in x.items() if not drop(k)}
    if isinstance(x, list):
        return [without(v, drop) for v in x]
    return x

def run_dependent(key):  # changes from run to run
    return key.startswith("seconds") or key.endswith("_seconds") or key == "threads"

def not_computed(key):  # `prt info --json` keys that are not prt's computation
    return run_dependent(key) or key in ("file", "bytes", "sh_basis", "run")

def container(data, header_size, table, sections, metadata, zeroed, h):
    """A PRTC or PRTG file: header, then each section; the metadata without run data."""
    header = bytearray(data[:header_size])
    for a, b in zeroed + [(table + 16 * metadata, table + 16 * metadata + 16)]:
        header[a:b] = bytes(b - a)
    h.update(header)
    for i in range(sections):
        offset, size = struct.unpack_from("<QQ", data, table + 16 * i)
        part = data[offset:offset + size]
        if i == metadata and size:
            part = json.dumps(without(json.loads(part), run_dependent), sort_keys=True).encode()
        h.update(struct.pack("<Q", len(part)) + part)

def content(path):
    data = open(path, "rb").read()
    h = hashlib.sha256()
    magic = data[:4]
    if magic == b"PRTC":    # .prt, SH or Haar (docs/FORMAT.md)
        container(data, 192, 72, 7, 6, [(56, 68)], h)
    elif magic == b"PRTG":  # .prtg (docs/FORMAT.md, "Glossy transfer files")
        container(data, 208, 80, 8, 7, [(64, 76)], h)
    elif magic == b"PRCP":  # .prtq (docs/GLOSSY_CPCA.md, "File format")
        order, channels, q, k, flags = struct.unpack_from("<5I", data, 12)
        v, = struct.unpack_from("<Q", data, 32)
        d = channels * order ** 4
        end = 64 + 4 * q * (k + 1) * d + (2 * v + 3) // 4 * 4 + 4 * v * k
        h.update(data[:48] + bytes(12) + data[60:end])
        if flags & 1:
            size, = struct.unpack_from("<Q", data, end)
            container(data[end + 8:end + 8 + size], 208, 80, 8, 7, [(64, 76)], h)
            end += 8 + size
        if flags & 2:  # the compression record (version 2): JSON without paths and run data
            size, = struct.unpack_from("<Q", data, end)     # (nor the source's size: its
            record = json.loads(data[end + 8:end + 8 + size])  # metadata once held run data)
            record = without(record, lambda k: run_dependent(k) or k in ("source_file",
                                                                          "source_bytes"))
            h.update(json.dumps(record, sort_keys=True).encode())
            end += 8 + size
        if end != len(data):
            sys.exit(f"{path}: the sections do not end the file")
    elif magic == b"PRTE":  # .prte: no metadata
        h.update(data)
    else:
        sys.exit(f"{path}: not a coefficient file")
    return h.hexdigest()[:16]

images, current = {}, None
for line in open("images.txt"):
    if " : " in line and not line.startswith(" "):
        current = line.split(" : ")[0].strip()
    elif "SHA-1:" in line:
        images[current] = "SHA-1: " + line.split("SHA-1:")[1].strip() + "\n"

for row in open("manifest.tsv"):
    label, kind, path = row.rstrip("\n").split("\t")
    if kind == "file":
        value = digest(open(path, "rb").read())
    elif kind == "content":
        value = content(path)
    elif kind == "image":
        if path not in images:
            sys.exit(f"behaviour-hashes.sh: iinfo gave no hash for {path}")
        value = digest(images[path].encode())
    elif kind == "metadata":
        meta = without(json.load(open(path)), not_computed)
        value = digest((json.dumps(meta, sort_keys=True) + "\n").encode())
    else:  # env: the JSON without the convention text and the file name
        d = json.load(open(path))
        d = {k: v for k, v in d.items() if k not in ("sh_basis", "basis", "file")}
        value = digest((json.dumps(d, sort_keys=True) + "\n").encode())
    print(f"{label:40s} {value}")
EOF
