#!/usr/bin/env bash
# scripts/fuzz.sh — builds the libFuzzer targets of fuzz/ with clang and
# -fsanitize=fuzzer,address,undefined, and runs each for N executions (default 1,000,000) from
# its seed corpus fuzz/corpus/<target>/ (new inputs go to build-fuzz/corpus/<target>/, so the
# committed seeds stay small). Findings (crash-*, leak-*, timeout-*, oom-*) are written to
# build-fuzz/findings/<target>/ and make the script fail.
#
# Usage: scripts/fuzz.sh [-n RUNS] [-t SECONDS] [-j JOBS] [-l BYTES] [TARGET...]
#   -n RUNS     executions per target (libFuzzer -runs), default 1000000
#   -t SECONDS  also stop a target after this much time (libFuzzer -max_total_time), default none
#   -j JOBS     worker processes per target sharing its corpus (RUNS split between them), default 1
#   -l BYTES    largest input (libFuzzer -max_len), default per target (max_len_of below)
#   TARGET      fuzz_transfer_file fuzz_glossy_file fuzz_cpca_file fuzz_emitter_responses
#               fuzz_haar_file fuzz_form_factor_cache fuzz_link_cache fuzz_part_file
#               fuzz_part_merge fuzz_merl_brdf fuzz_texture fuzz_scene_obj fuzz_scene_gltf fuzz_env_map
#               fuzz_env_map_exr (default: all)
# Environment: BUILD_DIR (default <repo>/build-fuzz), REGENERATE_CORPUS=1 rewrites the seeds,
# PRT_FUZZ_NO_INSTALL=1 fails instead of installing clang when it is missing (the ctest smoke run,
# tests/scripts/check_fuzz_smoke.sh, skips before calling this). The build uses ccache when present.
# Needs clang and libclang-rt-14-dev (scripts/install-deps.sh --for test installs them).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-fuzz}"
RUNS=1000000
TIME=0
JOBS=1
MAX_LEN=
while getopts "n:t:j:l:" opt; do
  case "$opt" in
    n) RUNS="$OPTARG" ;;
    t) TIME="$OPTARG" ;;
    j) JOBS="$OPTARG" ;;
    l) MAX_LEN="$OPTARG" ;;
    *) echo "usage: $0 [-n RUNS] [-t SECONDS] [-j JOBS] [-l BYTES] [TARGET...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
ALL_TARGETS=(fuzz_transfer_file fuzz_glossy_file fuzz_cpca_file fuzz_emitter_responses
  fuzz_haar_file fuzz_form_factor_cache fuzz_link_cache fuzz_part_file fuzz_part_merge
  fuzz_merl_brdf fuzz_texture fuzz_scene_obj fuzz_scene_gltf fuzz_env_map fuzz_env_map_exr)
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=("${ALL_TARGETS[@]}"); fi

# Inputs beyond a few KB only slow the binary formats down (their seeds are 0.3–4 KB); images
# and scenes get more room.
max_len_of() {
  if [ -n "$MAX_LEN" ]; then echo "$MAX_LEN"; return; fi
  case "$1" in
    fuzz_scene_* | fuzz_env_map*) echo 65536 ;;
    fuzz_texture) echo 16384 ;;
    fuzz_part_merge) echo 512 ;;  # operations on fixed parts: a few dozen bytes say a lot
    *) echo 8192 ;;
  esac
}

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  if [ "${PRT_FUZZ_NO_INSTALL:-0}" = 1 ]; then
    echo "fuzz.sh: clang++ or libFuzzer (libclang-rt-14-dev) missing" >&2
    exit 1
  fi
  "$ROOT/scripts/install-deps.sh" --for test
fi

launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$ROOT/fuzz" -B "$BUILD_DIR" -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" >/dev/null
CORPUS="$ROOT/fuzz/corpus"
missing=0
for t in "${ALL_TARGETS[@]}"; do [ -d "$CORPUS/$t" ] || missing=1; done
if [ "${REGENERATE_CORPUS:-0}" = 1 ] || [ "$missing" = 1 ]; then
  cmake --build "$BUILD_DIR" --target make_fuzz_corpus "${TARGETS[@]}" -j2
  "$BUILD_DIR/make_fuzz_corpus" "$CORPUS"
else
  cmake --build "$BUILD_DIR" --target "${TARGETS[@]}" -j2
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$ROOT/scripts/lsan-suppressions.txt:print_suppressions=0}"
status=0
for t in "${TARGETS[@]}"; do
  work="$BUILD_DIR/corpus/$t"
  findings="$BUILD_DIR/findings/$t"
  mkdir -p "$work" "$findings"
  echo "== $t: $RUNS runs" >&2
  start=$(date +%s)
  set +e
  # OpenEXR 3.1 allocates what a header claims (up to 2 GB from a 100-byte file); read_image
  # checks EXR headers first (relight/exr_header_check.h), but give the EXR target room for
  # whatever that check does not foresee.
  rss=2048
  if [ "$t" = fuzz_env_map_exr ]; then rss=4096; fi
  max_len=$(max_len_of "$t")
  # A table-sized MERL file is 35 MB written, read and checked under the sanitizers: seconds on
  # a loaded machine.
  timeout=10
  if [ "$t" = fuzz_merl_brdf ]; then timeout=60; fi
  # OpenImageIO keeps a per-thread error string after a failed PNG read (31 bytes, never freed);
  # scripts/lsan-suppressions.txt names the library, but only a full unwind of each allocation
  # sees its frames, which slows fuzz_texture from ~60 to ~10 executions/s. That target runs
  # without leak detection instead (prt's texture code holds memory only in containers).
  asan="$ASAN_OPTIONS"
  if [ "$t" = fuzz_texture ]; then asan="$ASAN_OPTIONS:detect_leaks=0"; fi
  if [ "$JOBS" -gt 1 ]; then
    # JOBS worker processes share the corpus, each running RUNS/JOBS executions; libFuzzer
    # writes their logs to fuzz-<i>.log in the working directory (here a folder per target)
    # and repeats each one in its own output when the worker exits.
    logs="$BUILD_DIR/logs/$t"
    rm -rf "$logs" && mkdir -p "$logs"
    (cd "$logs" && ASAN_OPTIONS="$asan" "$BUILD_DIR/$t" -runs=$((RUNS / JOBS)) -jobs="$JOBS" -workers="$JOBS" \
      -max_total_time="$TIME" -timeout="$timeout" -rss_limit_mb="$rss" -max_len="$max_len" \
      -print_final_stats=1 -artifact_prefix="$findings/" "$work" "$CORPUS/$t" \
      >"$BUILD_DIR/$t.log" 2>&1)
    rc=$?  # the parent's log repeats each worker's log as it exits
  else
    ASAN_OPTIONS="$asan" "$BUILD_DIR/$t" -runs="$RUNS" -max_total_time="$TIME" -timeout="$timeout" -rss_limit_mb="$rss" \
      -max_len="$max_len" -print_final_stats=1 -artifact_prefix="$findings/" \
      "$work" "$CORPUS/$t" 2>"$BUILD_DIR/$t.log"
    rc=$?
  fi
  set -e
  end=$(date +%s)
  # Summed over workers (one line per process).
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$BUILD_DIR/$t.log" | grep -o '[0-9]*$' |
    awk '{s += $1} END {if (NR) print s}' || true)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$BUILD_DIR/$t.log" | grep -o '[0-9]*$' |
    awk '{s += $1} END {if (NR) print s}' || true)
  coverage=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$BUILD_DIR/$t.log" | tail -1 || true)
  if [ -n "$(ls -A "$findings" 2>/dev/null)" ]; then rc=1; fi
  echo "$t: exit $rc, ${execs:-?} executions in $((end - start)) s (${rate:-?}/s), ${coverage:-cov ?}; log $BUILD_DIR/$t.log" >&2
  if [ "$rc" -ne 0 ]; then status=1; tail -40 "$BUILD_DIR/$t.log" >&2; fi
done
exit $status
