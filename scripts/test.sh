#!/usr/bin/env bash
# Installs what is missing (the demo's packages and the tests': Catch2, Google Benchmark, Node.js
# and three.js, clang, rsvg-convert), builds prt with its tests and benchmarks ON (scripts/build.sh,
# also in a build folder scripts/demo.sh configured without them), builds a consumer project
# against the *installed* package, then runs the whole test suite (ctest). Ends with ctest's
# summary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
bash "$root/scripts/build.sh"
if [ -f "$root/examples/CMakeLists.txt" ]; then
  bash "$root/scripts/test-consumer.sh"
fi
cd "$build"
ctest --output-on-failure -j "${PRT_JOBS:-$(nproc)}" --timeout 600
