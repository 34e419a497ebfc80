#!/usr/bin/env bash
# scripts/fuzz.sh — builds the libFuzzer targets of fuzz/ with clang and
# -fsanitize=fuzzer,address,undefined, and runs each for N executions (default 1,000,000) from
# its seed corpus fuzz/corpus/<target>/ (new inputs go to build-fuzz/corpus/<target>/, so the
# committed seeds stay small). Findings (crash-*, leak-*, timeout-*, oom-*) are written to
# build-fuzz/findings/<target>/ and make the script fail.
#
# Usage: scripts/fuzz.sh [-n RUNS] [-t SECONDS] [-j JOBS] [TARGET...]
#   -n RUNS     executions per target (libFuzzer -runs), default 1000000
#   -t SECONDS  also stop a target after this much time (libFuzzer -max_total_time), default none
#   -j JOBS     worker processes per target sharing its corpus (RUNS split between them), default 1
#   TARGET      fuzz_transfer_file fuzz_scene_obj fuzz_scene_gltf fuzz_env_map fuzz_env_map_exr
#               (default: all)
# Environment: BUILD_DIR (default <repo>/build-fuzz), REGENERATE_CORPUS=1 rewrites the seeds.
# Needs clang and libclang-rt-14-dev (scripts/install-deps.sh --for test installs them).
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build-fuzz}"
RUNS=1000000
TIME=0
JOBS=1
while getopts "n:t:j:" opt; do
  case "$opt" in
    n) RUNS="$OPTARG" ;;
    t) TIME="$OPTARG" ;;
    j) JOBS="$OPTARG" ;;
    *) echo "usage: $0 [-n RUNS] [-t SECONDS] [-j JOBS] [TARGET...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then
  TARGETS=(fuzz_transfer_file fuzz_scene_obj fuzz_scene_gltf fuzz_env_map fuzz_env_map_exr)
fi

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  "$ROOT/scripts/install-deps.sh" --for test
fi

cmake -S "$ROOT/fuzz" -B "$BUILD_DIR" -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$BUILD_DIR" --target make_fuzz_corpus "${TARGETS[@]}" -j2

CORPUS="$ROOT/fuzz/corpus"
if [ "${REGENERATE_CORPUS:-0}" = 1 ] || [ ! -d "$CORPUS/fuzz_transfer_file" ] ||
  [ ! -d "$CORPUS/fuzz_env_map_exr" ]; then
  "$BUILD_DIR/make_fuzz_corpus" "$CORPUS"
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
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
  if [ "$JOBS" -gt 1 ]; then
    # JOBS worker processes share the corpus, each running RUNS/JOBS executions; libFuzzer
    # writes their logs to fuzz-<i>.log in the working directory (here a folder per target)
    # and repeats each one in its own output when the worker exits.
    logs="$BUILD_DIR/logs/$t"
    rm -rf "$logs" && mkdir -p "$logs"
    (cd "$logs" && "$BUILD_DIR/$t" -runs=$((RUNS / JOBS)) -jobs="$JOBS" -workers="$JOBS" \
      -max_total_time="$TIME" -timeout=10 -rss_limit_mb="$rss" -max_len=65536 \
      -print_final_stats=1 -artifact_prefix="$findings/" "$work" "$CORPUS/$t" \
      >"$BUILD_DIR/$t.log" 2>&1)
    rc=$?  # the parent's log repeats each worker's log as it exits
  else
    "$BUILD_DIR/$t" -runs="$RUNS" -max_total_time="$TIME" -timeout=10 -rss_limit_mb="$rss" \
      -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings/" \
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
  if [ -n "$(ls -A "$findings" 2>/dev/null)" ]; then rc=1; fi
  echo "$t: exit $rc, ${execs:-?} executions in $((end - start)) s (${rate:-?}/s); log $BUILD_DIR/$t.log" >&2
  if [ "$rc" -ne 0 ]; then status=1; tail -40 "$BUILD_DIR/$t.log" >&2; fi
done
exit $status
