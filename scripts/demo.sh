#!/usr/bin/env bash
# Installs what is missing, builds prt, and runs the main job on the bundled data:
# `prt demo` bakes data/demo.glb, relights it under data/sky.hdr and writes out/demo.png.
# Extra arguments go to `prt demo` (e.g. --quick, -o DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh" >/dev/null
cd "$root"
"$build/bin/prt" demo "$@"
