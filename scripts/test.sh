#!/usr/bin/env bash
# Installs what is missing, builds prt, runs the whole test suite (ctest), then builds a
# consumer project against the *installed* package. Ends with ctest's summary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh"
if [ -f "$root/examples/CMakeLists.txt" ]; then
  bash "$root/scripts/test-consumer.sh"
fi
cd "$build"
ctest --output-on-failure -j "${PRT_JOBS:-$(nproc)}" --timeout 600
