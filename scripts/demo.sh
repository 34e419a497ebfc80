#!/usr/bin/env bash
# Installs what the `prt` program needs (scripts/install-deps.sh --for demo: no test framework,
# benchmark library, Node.js or clang), builds only the `prt_cli` target, and runs the main job
# on the bundled data: `prt demo` bakes data/demo.glb, relights it under data/sky.hdr and writes
# out/demo.png. Extra arguments go to `prt demo` (e.g. --quick, -o DIR).
#
# A new build folder is configured with PRT_BUILD_TESTS=OFF and PRT_BUILD_BENCHMARKS=OFF (tests
# need Catch2, benchmarks Google Benchmark, neither installed here). A folder that is already
# configured keeps its options: scripts/build.sh and scripts/test.sh configure tests and
# benchmarks ON themselves, so they build and reuse what the demo compiled, and a demo run after
# them does not take the tests out of that folder's ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
jobs="${PRT_JOBS:-$(nproc)}"
bash "$root/scripts/install-deps.sh" --for demo
options=()
if [ ! -f "$build/CMakeCache.txt" ]; then
  options=(-DPRT_BUILD_TESTS=OFF -DPRT_BUILD_BENCHMARKS=OFF)
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${PRT_BUILD_TYPE:-Release}" "${options[@]}" >/dev/null
echo "demo: building prt (build/bin/prt)" >&2
cmake --build "$build" -j "$jobs" --target prt_cli >/dev/null
cd "$root"
"$build/bin/prt" demo "$@"
