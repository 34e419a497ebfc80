#!/usr/bin/env bash
# Install everything prt needs to build and test on Debian 12, as root.
# Does nothing when every package is already present.
#   1. Debian packages (apt), including Node.js and npm for the glTF viewer check.
#   2. The npm packages of tests/viewer (three.js, pinned by its package-lock.json) into
#      tests/viewer/node_modules, with `npm ci`. Nothing is downloaded at build or test time.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

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
# Node.js and npm (tests/viewer): Debian's packages, unless node and npm are already on the
# PATH (a Node.js from elsewhere conflicts with Debian's npm package).
command -v node >/dev/null 2>&1 || missing+=(nodejs)
command -v npm >/dev/null 2>&1 || missing+=(npm)

if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# three.js for the viewer check, at the version package-lock.json pins.
viewer="$root/tests/viewer"
wanted="$(cd "$viewer" && node -p "require('./package-lock.json').packages['node_modules/three'].version")"
have="$(cd "$viewer" && node -p "try { require('./node_modules/three/package.json').version } catch (e) { '' }")"
if [ "$have" != "$wanted" ]; then
  echo "install-deps: installing three@$wanted into tests/viewer/node_modules (npm ci)" >&2
  (cd "$viewer" && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error >/dev/null)
fi
