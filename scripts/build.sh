#!/usr/bin/env bash
# Configures and builds aggpack into build/ (or $AGGPACK_BUILD_DIR). Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${AGGPACK_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=${AGGPACK_BUILD_TYPE:-Release} "$@"
cmake --build "$build_dir" -j "$(nproc)"
