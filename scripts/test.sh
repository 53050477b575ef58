#!/usr/bin/env bash
# Fresh Debian bookworm, as root: install dependencies, build with warnings as errors, and run
# every test. `scripts/test.sh --sanitize` builds into build-asan/ with AddressSanitizer +
# UndefinedBehaviorSanitizer and runs the suite there, except the tests labelled external-solver
# (a full ccx or yade run on a file our code wrote) and physics-trend (minutes of simulation that
# check what the physics measures); tests/labels.cmake names the tests that run their code under
# the sanitizers. The sanitized build is compiled at -O1 -g1 (half
# the compile time of -O2 -g). After scripts/quickstart.sh, the normal build compiles nothing:
# both use scripts/build.sh's flags.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${AGGPACK_SKIP_INSTALL:-0}" != 1 ]; then scripts/install-deps.sh; fi
if [ "${1:-}" = "--sanitize" ]; then
  shift
  export AGGPACK_BUILD_DIR=build-asan AGGPACK_BUILD_TYPE=RelWithDebInfo
  # Our own code, the physics (sim/) included: Bullet itself is Debian's uninstrumented library.
  # OpenGL (Mesa) is left out of the sanitized build, and so is the Python module (an
  # ASan-instrumented extension needs the ASan runtime preloaded into the uninstrumented python3
  # interpreter, whose own allocations then report leaks); the module's pytest suite runs in the
  # normal build. -O1 -g1
  # (ASan's recommended level; line tables are all a sanitizer report needs) instead of
  # RelWithDebInfo's -O2 -g: GCC 12 compiles our tree with ASan + UBSan in about half the CPU time.
  # (Clang 14 compiles it faster still, but its build does not reproduce GCC's numbers: the golden
  # densify and pack-random cases and ObjExport.MeshioReadsVerticesAndFaces fail there.)
  scripts/build.sh -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DAGGPACK_SANITIZE=ON \
    -DAGGPACK_BUILD_BENCH=OFF -DAGGPACK_BUILD_GUI=OFF -DAGGPACK_BUILD_RENDER=OFF \
    -DAGGPACK_BUILD_SIM=ON -DAGGPACK_BUILD_PYTHON=OFF "$@"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  export AGGPACK_SANITIZED=1
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE 'external-solver|physics-trend'
else
  echo "test: building (nothing to compile after scripts/quickstart.sh; about 9 minutes from scratch"
  echo "on 2 cores), then the test suite (about 6 minutes on 2 cores)"
  scripts/build.sh "$@"
  ctest --test-dir build --output-on-failure -j "$(nproc)"
fi
