#!/usr/bin/env bash
# Runs scripts/behaviour-hashes.sh --quick on a prt binary and checks that it completes and
# prints exactly the labels of behaviour_hashes_labels.txt, in order, each with a 16-digit hash,
# and no hash of an empty output. When the script gains a line, add its label there.
# Exit 77 (skipped) without iinfo (openimageio-tools, installed by scripts/install-deps.sh).
# Usage: check_behaviour_hashes.sh PRT_BINARY SOURCE_DIR
set -euo pipefail
prt="$1"
source="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
command -v iinfo >/dev/null || { echo "skipped: iinfo (openimageio-tools) is not installed"; exit 77; }
out="$(bash "$source/scripts/behaviour-hashes.sh" --quick "$prt")"
printf '%s\n' "$out"
malformed="$(grep -vE '^[^ ].* [0-9a-f]{16}$' <<<"$out" || true)"
if [[ -n "$malformed" ]]; then
  echo "FAILED: lines without a label and a 16-digit hash:"; echo "$malformed"; exit 1
fi
# SHA-256 of nothing: an output that came out empty.
empty="$(grep -E ' e3b0c44298fc1c14$' <<<"$out" || true)"
if [[ -n "$empty" ]]; then
  echo "FAILED: empty outputs:"; echo "$empty"; exit 1
fi
if ! diff <(sed -E 's/ +[0-9a-f]{16}$//' <<<"$out") "$here/behaviour_hashes_labels.txt"; then
  echo "FAILED: the labels differ from $here/behaviour_hashes_labels.txt (< printed, > expected)"
  exit 1
fi
echo "behaviour-hashes.sh --quick: $(wc -l <<<"$out") lines, as expected"
