#!/usr/bin/env bash
# Installs what is missing, builds prt, and runs the main job on the bundled data.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh" >/dev/null
cd "$root"
"$build/bin/prt" env data/sky.hdr --order 3
