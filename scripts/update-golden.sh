#!/usr/bin/env bash
# Re-renders the golden-image set (tests/golden/README.md) and replaces the references whose
# pixels changed; prints per image whether and how much it changed (pixels beyond the test's
# tolerance, max and mean difference) and appends the date, the reason, the commit and those
# figures to tests/golden/CHANGES.md.
#
# Usage: scripts/update-golden.sh "REASON" [NAME...]
#   REASON  why the images change (required: the log says why each reference is what it is)
#   NAME    only these images (prt_golden list names them); default: the whole set
# Environment: PRT_BUILD_DIR (default build/). The renders, their logs and a difference image per
# changed reference (NAME_diff.png: grey within tolerance, red to yellow beyond) stay in
# $PRT_BUILD_DIR/golden-update/ for you to look at before committing.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"

reason="${1:-}"
if [ -z "${reason//[[:space:]]/}" ]; then
  echo "update-golden: give the reason the images change, e.g." >&2
  echo "  scripts/update-golden.sh \"the sampler's scrambling changed\" [NAME...]" >&2
  exit 2
fi
shift

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j "${PRT_JOBS:-$(nproc)}" --target prt_cli prt_golden >/dev/null

work="$build/golden-update"
rm -rf "$work"
mkdir -p "$work"
report="$work/report.txt"
"$build/tests/golden/prt_golden" update "$build/bin/prt" "$work" "$@" | tee "$report"

commit="$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [ -n "$(git -C "$root" status --porcelain -- . ':!tests/golden/references' ':!tests/golden/CHANGES.md' 2>/dev/null)" ]; then
  commit="$commit with uncommitted changes"
fi
{
  echo
  echo "## $(date -u +%Y-%m-%d) — $reason"
  echo
  echo "Rendered from $commit."
  echo
  sed 's/^/- /' "$report"
} >>"$root/tests/golden/CHANGES.md"

echo "update-golden: appended to tests/golden/CHANGES.md; renders, logs and difference images" \
  "are in $work: look at every changed image before committing"
