#!/usr/bin/env bash
# Fresh Debian bookworm, as root: install dependencies, build with warnings as errors, and run
# every test. `scripts/test.sh --sanitize` builds into build-asan/ with AddressSanitizer +
# UndefinedBehaviorSanitizer and runs the suite there, except the tests labelled external-solver
# (a full ccx or yade run on a file our code wrote; tests/labels.cmake says where that file's
# writer is tested under the sanitizers). The sanitized build uses Debian's clang 14 (as
# scripts/fuzz.sh does): with ASan + UBSan it compiles our tree in about a third of GCC 12's CPU
# time (GCC stays the compiler of the Release build). A build-asan/ configured with GCC before is
# reconfigured from scratch once.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${AGGPACK_SKIP_INSTALL:-0}" != 1 ]; then scripts/install-deps.sh; fi
if [ "${1:-}" = "--sanitize" ]; then
  shift
  export AGGPACK_BUILD_DIR=build-asan AGGPACK_BUILD_TYPE=RelWithDebInfo
  # Our own code only: OpenGL (Mesa) and Bullet are left out of the sanitized build. Clang 14 does
  # not define GCC's __SANITIZE_ADDRESS__ (tests/geom/overlap_test.cpp shrinks its brute-force
  # sweeps by it, Eigen picks its aligned malloc by it): defined here as GCC defines it.
  scripts/build.sh -DCMAKE_C_COMPILER="${CC_SANITIZE:-clang-14}" \
    -DCMAKE_CXX_COMPILER="${CXX_SANITIZE:-clang++-14}" -DCMAKE_CXX_FLAGS=-D__SANITIZE_ADDRESS__=1 \
    -DAGGPACK_WERROR=ON -DAGGPACK_SANITIZE=ON \
    -DAGGPACK_BUILD_BENCH=OFF -DAGGPACK_BUILD_GUI=OFF -DAGGPACK_BUILD_RENDER=OFF \
    -DAGGPACK_BUILD_SIM=OFF "$@"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  export AGGPACK_SANITIZED=1
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE external-solver
else
  scripts/build.sh -DAGGPACK_WERROR=ON "$@"
  ctest --test-dir build --output-on-failure -j "$(nproc)"
fi
