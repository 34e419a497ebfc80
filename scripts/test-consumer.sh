#!/usr/bin/env bash
# Installs the prt build into a temporary prefix and builds + runs examples/ (a tiny
# engine-like project using find_package(prt)) against the *installed* package only.
# Exits non-zero if installing, configuring, building or running the consumer fails.
#   PRT_BUILD_DIR  the build tree to install (default: <repo>/build; must be built already)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PRT_BUILD_DIR:-$root/build}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/prt-consumer.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

echo "test-consumer: installing $build into $tmp/prefix"
cmake --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" \
  || { cat "$tmp/install.log"; echo "test-consumer: install failed" >&2; exit 1; }

# Only the prefix may provide prt: no package registry, no source tree on the include path.
cmake -S "$root/examples" -B "$tmp/build" \
  -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
  -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF > "$tmp/configure.log" \
  || { cat "$tmp/configure.log"; echo "test-consumer: configure failed" >&2; exit 1; }
cmake --build "$tmp/build" -j "${PRT_JOBS:-2}" > "$tmp/build.log" 2>&1 \
  || { cat "$tmp/build.log"; echo "test-consumer: build failed" >&2; exit 1; }
(cd "$tmp/build" && ctest --output-on-failure) \
  || { echo "test-consumer: the consumer's tests failed" >&2; exit 1; }
echo "test-consumer: OK (find_package(prt) from the installed prefix works)"
