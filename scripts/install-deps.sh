#!/usr/bin/env bash
# Installs what prt needs on Debian 12, as root (or through sudo). Does nothing when every package
# is already present. This is the one place that names the packages.
#
# Usage: scripts/install-deps.sh [--for demo|test]
#   --for demo  what building the `prt` program needs (scripts/demo.sh): the compiler, CMake and
#               the libraries prt links. No test framework, no Node.js, no clang.
#   --for test  (the default) the demo's packages plus what only the tests, benchmarks and fuzzers
#               use (scripts/test.sh, scripts/build.sh, scripts/fuzz.sh), and the npm packages of
#               tests/viewer (three.js, pinned by its package-lock.json) into
#               tests/viewer/node_modules, with `npm ci`. Nothing is downloaded at build or test
#               time.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

usage() { echo "usage: scripts/install-deps.sh [--for demo|test]" >&2; exit 2; }
side="test"
while [ $# -gt 0 ]; do
  case "$1" in
    --for) [ $# -ge 2 ] || usage; side="$2"; shift 2 ;;
    --for=*) side="${1#--for=}"; shift ;;
    *) usage ;;
  esac
done
case "$side" in demo | test) ;; *) usage ;; esac

# Building the `prt` program (PRT_BUILD_TESTS=OFF, PRT_BUILD_BENCHMARKS=OFF).
DEMO_PACKAGES=(
  g++ cmake make                       # a fresh Debian 12 has no compiler
  libembree-dev libtbb-dev libglm-dev  # ray casting (scene/)
  libopenimageio-dev                   # image I/O plugin (scene/plugin/); Imath comes with it
  openimageio-tools libopencv-core-dev # find_package(OpenImageIO) fails without them: its CMake
                                       # files check that oiiotool & co. and /usr/include/opencv4
                                       # exist
  libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev  # scene loaders, JSON output
  libcli11-dev                         # the command line (cli/)
  libcpp-httplib-dev                   # the HTTP server of `prt view` (cli/view/)
)
# Only the tests, benchmarks and fuzzers.
TEST_PACKAGES=(
  catch2                               # tests/ (Catch2 v2)
  libbenchmark-dev                     # bench/ (Google Benchmark)
  librsvg2-bin                         # rsvg-convert: the PNG plots of `prt report`, which the
                                       # report tests exercise (without it: SVG only, tests pass)
  clang libclang-rt-14-dev             # scripts/fuzz.sh (libFuzzer)
  chromium                             # tests/viewer: the real-browser test of `prt view`, headless
  curl                                 # tests/viewer: the requests `prt view`'s server refuses
  slurm-wlm munge                      # scripts/slurm-local.sh: a single-node Slurm (slurmctld,
                                       # slurmd, sbatch/squeue/sacct/scancel, munged) that
                                       # tests/scripts/check_slurm_farm.sh runs the examples on
)
# Not needed by either side: pkg-config (no find module calls it) and libopenexr-dev (OpenImageIO
# 2.4 takes half and Imath from libimath-dev; prt includes no OpenEXR header).

packages=("${DEMO_PACKAGES[@]}")
if [ "$side" = test ]; then packages+=("${TEST_PACKAGES[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ "$side" = test ]; then
  # Node.js and npm (tests/viewer): Debian's packages, unless node and npm are already on the
  # PATH (a Node.js from elsewhere conflicts with Debian's npm package).
  command -v node >/dev/null 2>&1 || missing+=(nodejs)
  command -v npm >/dev/null 2>&1 || missing+=(npm)
fi

if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ "$side" = test ]; then
  # three.js for the viewer check and `prt view`'s page, puppeteer-core for the real-browser test
  # (it drives Debian's chromium; it downloads no browser), at the versions package-lock.json pins.
  viewer="$root/tests/viewer"
  for package in three puppeteer-core; do
    wanted="$(cd "$viewer" && node -p "require('./package-lock.json').packages['node_modules/$package'].version")"
    have="$(cd "$viewer" && node -p "try { require('./node_modules/$package/package.json').version } catch (e) { '' }")"
    if [ "$have" != "$wanted" ]; then
      echo "install-deps: installing the packages of tests/viewer/package-lock.json (npm ci)" >&2
      (cd "$viewer" && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error >/dev/null)
      break
    fi
  done
fi
