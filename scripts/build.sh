#!/usr/bin/env bash
# Installs what is missing (scripts/install-deps.sh --for test: the demo's packages and the
# tests'), then configures and builds prt (Release) into build/ with the tests and benchmarks ON,
# also in a folder scripts/demo.sh configured without them.
# Usage: scripts/build.sh [extra cmake -D options] (they come last, so -DPRT_BUILD_TESTS=OFF wins)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
bash "$root/scripts/install-deps.sh" --for test
jobs="${PRT_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${PRT_BUILD_TYPE:-Release}" \
  -DPRT_BUILD_TESTS=ON -DPRT_BUILD_BENCHMARKS=ON "$@" >/dev/null
cmake --build "$build" -j "$jobs"
