#!/usr/bin/env bash
# Is the machine code of the relighting kernels (prt/src/diffuse/relighter.cpp, glossy/kernel.cpp,
# glossy/cpca_kernel.cpp) the same in two builds? One line per kernel, "identical" or "DIFFERENT" with
# the functions that changed (--diff: their normalised disassembly). The objects are found by
# the symbols they define, so a source may move; addresses, label numbering and the placement
# of unrelated data are normalised away (scripts/kernel_code.py says how).
# Exit status: 0 all identical, 1 one differs, 2 a kernel not found.
# Usage: scripts/kernel-code.sh [--diff] OLD_BUILD NEW_BUILD
#        scripts/kernel-code.sh --list BUILD   (where the kernels' objects are)
set -euo pipefail
exec python3 "$(dirname "${BASH_SOURCE[0]}")/kernel_code.py" "$@"
