#!/usr/bin/env bash
# Install everything prt needs to build and test on Debian 12, as root.
# Does nothing when every package is already present.
set -euo pipefail

PACKAGES=(
  g++ cmake make pkg-config
  libembree-dev libglm-dev
  libopenimageio-dev openimageio-tools libopencv-core-dev
  libopenexr-dev libtinygltf-dev catch2 libtbb-dev
  libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
  libbenchmark-dev
  librsvg2-bin
  clang libclang-rt-14-dev  # scripts/fuzz.sh (libFuzzer)
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
