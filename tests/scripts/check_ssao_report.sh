#!/usr/bin/env bash
# `prt report --ssao` end to end in headless Chromium (--quick, the demo scene, about 15 s):
# status 0, every file written, and figures that must hold — the baked per-vertex AO rendered by
# the page agrees with the per-pixel ray-traced AO (relative RMS < 0.08: the page's G-buffer, its
# cameras and the traced points are registered; 64 rays and 64 samples give ~0.03), GTAO against
# AO within the radius beats classic SSAO against it, and the contact and edge regions are not
# empty. Then the refusals: a Chromium that does not exist (PRT_CHROMIUM) is said in one line with
# status 1 and nothing written, and so is a write that fails (file size limit).
# Skips (status 77) without Chromium, node or tests/viewer's puppeteer-core, or a prt built
# without the viewer.
# Usage: check_ssao_report.sh PRT_BINARY SOURCE_DIR
set -euo pipefail
prt="$(realpath "$1")"
source_dir="$(realpath "$2")"
if ! command -v chromium >/dev/null && ! command -v chromium-browser >/dev/null; then
  echo "SKIP: Chromium is not installed (scripts/install-deps.sh --for test)"; exit 77
fi
command -v node >/dev/null || { echo "SKIP: node is not installed"; exit 77; }
[[ -f "$source_dir/tests/viewer/node_modules/puppeteer-core/package.json" ]] ||
  { echo "SKIP: puppeteer-core is not installed in tests/viewer (scripts/install-deps.sh --for test)"; exit 77; }
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
cd "$scratch"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

status=0
"$prt" report --ssao "$source_dir/data/demo.glb" -o out --quick --quiet >stdout.txt 2>err.txt ||
  status=$?
if grep -q "built without the viewer" err.txt; then
  echo "SKIP: this prt was built without the viewer (cpp-httplib)"; exit 77
fi
[[ $status == 0 ]] || { fail "prt report --ssao exited with $status: $(head -1 err.txt)"; exit 1; }
for f in ao.prt ssao_errors.csv ssao_errors.json summary.md ssao_cam0.png ssao_cam1.png; do
  [[ -s "out/$f" ]] || fail "out/$f was not written"
done
python3 - out/ssao_errors.json <<'PY' || failures=$((failures + 1))
import json, sys
j = json.load(open(sys.argv[1]))
total = {(r["estimate"], r["truth"]): r for r in j["results"] if r["camera"] == "all"}
baked = total[("baked", "ao")]["all"]["relative_rms"]
ssao = total[("ssao", "obscurance")]["all"]["relative_rms"]
gtao = total[("gtao", "obscurance")]["all"]["relative_rms"]
print(f"baked vs AO {baked:.3f}, SSAO vs AO within R {ssao:.3f}, GTAO vs AO within R {gtao:.3f}")
ok = baked < 0.08 and gtao < ssao and total[("ssao", "ao")]["contact"]["pixels"] > 0 \
    and total[("ssao", "ao")]["edge"]["pixels"] > 0
if not ok: print("FAIL: the figures above do not hold")
sys.exit(0 if ok else 1)
PY

# No browser: one line, status 1, nothing written.
status=0
PRT_CHROMIUM=/nonexistent/chromium "$prt" report --ssao "$source_dir/data/demo.glb" -o none \
  --quick >/dev/null 2>err.txt || status=$?
[[ $status == 1 ]] || fail "PRT_CHROMIUM=/nonexistent: exit status $status, expected 1"
[[ $(wc -l < err.txt) == 1 ]] && grep -q "PRT_CHROMIUM" err.txt ||
  fail "PRT_CHROMIUM=/nonexistent: expected one line naming it, got: $(cat err.txt)"
[[ ! -e none ]] || fail "PRT_CHROMIUM=/nonexistent: the output folder was created"

# A write that fails (files limited to 16 KB): one line naming the file, status 1, no file.
status=0
(trap '' XFSZ; ulimit -f 16; exec "$prt" report --ssao "$source_dir/data/demo.glb" -o limited \
  --quick --quiet) >/dev/null 2>err.txt || status=$?
[[ $status == 1 ]] || fail "files limited to 16 KB: exit status $status, expected 1"
[[ $(wc -l < err.txt) == 1 ]] && grep -q "File too large" err.txt ||
  fail "files limited to 16 KB: expected one line 'File too large', got: $(cat err.txt)"
[[ -z "$(ls -A limited 2>/dev/null)" ]] || fail "files limited to 16 KB: left $(ls limited)"

[[ $failures == 0 ]] && echo "ok: prt report --ssao" || exit 1
