#!/usr/bin/env bash
# scripts/kernel-code.sh against a build: it finds the three kernels' objects; the build against
# itself is identical (exit 0); copies of the objects at other paths (as after moving the
# sources) are identical; the same copies with one byte of a constant of the glossy kernel
# flipped make exactly that kernel DIFFERENT (exit 1).
# Usage: check_kernel_code.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR
set -euo pipefail
build="$1"
source="$2"
scratch="$3"
script="$source/scripts/kernel-code.sh"
fail() { echo "FAILED: $*"; exit 1; }

"$script" --list "$build" || fail "a kernel's object file was not found in $build"
out="$("$script" "$build" "$build")" || fail "the build against itself: exit $?"$'\n'"$out"
echo "$out"
[[ $(grep -c '^[a-z_]* *identical ' <<<"$out") == 3 ]] || fail "not three identical kernels"

rm -rf "$scratch"
mkdir -p "$scratch/old/lib" "$scratch/new/moved/deeper"
while read -r name path; do
  cp "$path" "$scratch/old/lib/$name.o"  # named by kernel: sources of two subjects may share a name
  cp "$path" "$scratch/new/moved/deeper/$name.o"
done < <("$script" --list "$build")
out="$("$script" "$scratch/old" "$scratch/new")" || fail "moved copies: exit $?"$'\n'"$out"
[[ $(grep -c '^[a-z_]* *identical ' <<<"$out") == 3 ]] || fail "moved copies not identical"$'\n'"$out"

# One byte of the first constant-pool entry of the glossy kernel's object.
glossy="$scratch/new/moved/deeper/glossy_kernel.o"
python3 - "$source/scripts" "$glossy" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
import kernel_code
elf = kernel_code.Elf(sys.argv[2])
pool = next(s for s in elf.sections if s["name"].startswith(".rodata.cst") and s["size"])
data = bytearray(elf.data)
data[pool["off"]] ^= 0x40
open(sys.argv[2], "wb").write(data)
PY
status=0
out="$("$script" "$scratch/old" "$scratch/new")" || status=$?
echo "$out"
[[ $status == 1 ]] || fail "a changed constant: exit $status, expected 1"
grep -q '^glossy_kernel *DIFFERENT ' <<<"$out" || fail "the glossy kernel not reported DIFFERENT"
[[ $(grep -c '^[a-z_]* *identical ' <<<"$out") == 2 ]] || fail "the other two kernels not identical"
echo "kernel-code.sh: identical, moved, changed constant: as expected"
