#!/usr/bin/env bash
# Fresh Debian bookworm, as root: install dependencies, build with warnings as errors, and run
# every test. `scripts/test.sh --sanitize` builds into build-asan/ with AddressSanitizer +
# UndefinedBehaviorSanitizer and runs the suite there.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${AGGPACK_SKIP_INSTALL:-0}" != 1 ]; then scripts/install-deps.sh; fi
if [ "${1:-}" = "--sanitize" ]; then
  shift
  export AGGPACK_BUILD_DIR=build-asan AGGPACK_BUILD_TYPE=RelWithDebInfo
  # Our own code only: OpenGL (Mesa) and Bullet are left out of the sanitized build.
  scripts/build.sh -DAGGPACK_WERROR=ON -DAGGPACK_SANITIZE=ON -DAGGPACK_BUILD_BENCH=OFF \
    -DAGGPACK_BUILD_GUI=OFF -DAGGPACK_BUILD_RENDER=OFF -DAGGPACK_BUILD_SIM=OFF
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  export AGGPACK_SANITIZED=1
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)"
else
  scripts/build.sh -DAGGPACK_WERROR=ON "$@"
  ctest --test-dir build --output-on-failure -j "$(nproc)"
fi
