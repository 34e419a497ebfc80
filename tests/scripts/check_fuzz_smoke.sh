#!/usr/bin/env bash
# The fuzz smoke run: scripts/fuzz.sh builds every libFuzzer target of fuzz/ (clang,
# -fsanitize=fuzzer,address,undefined; a standalone build of sh, prt, scene, bake, radiosity and
# relight in BUILD_DIR) and runs each for RUNS executions (at most 8 s) from its committed corpus
# fuzz/corpus/<target>/, which replays every kept regression input. Fails when the build breaks
# or any target finds a crash, leak, timeout or broken invariant. Skips (exit 77) only when clang
# or its libFuzzer runtime is missing: `scripts/install-deps.sh --for test` installs both.
# Usage: check_fuzz_smoke.sh SOURCE_DIR BUILD_DIR [RUNS]
set -euo pipefail
source="$1"
build="$2"
runs="${3:-10000}"
if ! command -v clang++ >/dev/null; then
  echo "SKIPPED: clang++ not found (bash scripts/install-deps.sh --for test installs it)"
  exit 77
fi
if ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "SKIPPED: libFuzzer runtime not found (libclang-rt-14-dev; bash scripts/install-deps.sh --for test)"
  exit 77
fi
start=$(date +%s)
rm -rf "$build/corpus" "$build/findings"  # each run starts from the committed corpus alone
BUILD_DIR="$build" PRT_FUZZ_NO_INSTALL=1 bash "$source/scripts/fuzz.sh" -n "$runs" -t 8
echo "fuzz smoke: build and $runs runs per target in $(($(date +%s) - start)) s"
