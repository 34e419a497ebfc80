#!/usr/bin/env bash
# scripts/test-sanitizers.sh — builds the test suite with AddressSanitizer + UndefinedBehavior-
# Sanitizer (-DPRT_SANITIZE=ON: -fsanitize=address,undefined -fno-sanitize-recover=undefined)
# and runs it. Any sanitizer report fails the test that triggered it.
#
# Usage: scripts/test-sanitizers.sh [--all]
#   default  the short CI pass: the numerics, sh/, prt/, scene/, bake/ and stability test executables
#            (the runtime library, the SH maths, scene loading, the baker and the stiff cases);
#   --all    every test target and the whole ctest suite.
# Environment: BUILD_DIR (default <repo>/build-asan), JOBS (default 2).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-asan}"
JOBS="${JOBS:-2}"
ALL=0
if [ "${1:-}" = "--all" ]; then ALL=1; fi

SHORT_TARGETS=(test_numerics test_sh_core test_sh_env test_prt_runtime test_scene test_transfer_baker
               test_stability)

start=$(date +%s)
cmake -S "$ROOT" -B "$BUILD_DIR" -DPRT_SANITIZE=ON -DPRT_BUILD_BENCHMARKS=OFF \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
if [ "$ALL" = 1 ]; then
  cmake --build "$BUILD_DIR" -j"$JOBS"
  regex='.*'
else
  cmake --build "$BUILD_DIR" --target "${SHORT_TARGETS[@]}" -j"$JOBS"
  regex="^($(IFS='|'; echo "${SHORT_TARGETS[*]}")):"  # ctest names are "target:case"
fi
built=$(date +%s)

# Leak checking stays on; TBB's worker threads and Embree's device are joined/released at exit.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}"
# Leaks inside third-party libraries that prt cannot free (listed, with why, in the file).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$ROOT/scripts/lsan-suppressions.txt:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
set +e
ctest --test-dir "$BUILD_DIR" -R "$regex" -j"$JOBS" --output-on-failure --timeout 600
rc=$?
set -e
end=$(date +%s)
echo "test-sanitizers: build $((built - start)) s, tests $((end - built)) s, exit $rc" >&2
exit $rc
