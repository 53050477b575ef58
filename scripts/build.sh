#!/usr/bin/env bash
# Configures and builds aggpack into build/ (or $AGGPACK_BUILD_DIR), warnings as errors (so
# scripts/quickstart.sh and scripts/test.sh share one build: the second compiles nothing). Compiles
# go through ccache when it is installed (cmake/ccache.cmake). Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${AGGPACK_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${AGGPACK_BUILD_TYPE:-Release} \
  -DAGGPACK_WERROR=ON "$@"
cmake --build "$build_dir" -j "$(nproc)"
