#!/usr/bin/env bash
# clang-tidy (Debian's clang-tidy 14) with the project's .clang-tidy (naming rules + cheap bugprone
# checks, warnings are errors) over every C++ file the build compiles: src/, app/ (CLI and GUI),
# python/ (the module), tests/ and bench/, and the headers they include from include/aggpack, src/,
# app/, python/ and tests/.
# Configures (does not build) build-tidy/ with every part on, for its compile_commands.json.
#
#   scripts/tidy.sh [FILE_REGEX]     e.g. scripts/tidy.sh 'src/io/' (default: all our files)
#
# Environment: AGGPACK_TIDY_JOBS (default 2), AGGPACK_TIDY_BUILD_DIR (default build-tidy).
# A finding that must stay gets `// NOLINT(check-name): reason` on its line.
# Cost: about 11.5 min of CPU for the 155 files (about 6 min on 2 idle cores).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build_dir=${AGGPACK_TIDY_BUILD_DIR:-build-tidy}
jobs=${AGGPACK_TIDY_JOBS:-2}
tidy=$(command -v clang-tidy-14 || command -v clang-tidy)
runner=$(command -v run-clang-tidy-14 || command -v run-clang-tidy)
mkdir -p "$build_dir"
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DAGGPACK_BUILD_TESTS=ON -DAGGPACK_BUILD_BENCH=ON >"$build_dir/configure.log" 2>&1 || {
  cat "$build_dir/configure.log"
  exit 1
}
files=${1:-'(src|app|python|tests|bench)/'}
SECONDS=0
# -Wno-unknown-warning-option: clang does not know GCC's -Wno-restrict (CMakeLists.txt).
"$runner" -clang-tidy-binary "$tidy" -p "$build_dir" -j "$jobs" -quiet \
  -extra-arg=-Wno-unknown-warning-option "^$root/$files" >"$build_dir/tidy.log" 2>&1 || status=$?
# Findings once each (a header's finding is reported by every file that includes it), no colours.
sed 's/\x1b\[[0-9;]*m//g' "$build_dir/tidy.log" | grep -E 'warning:|error:' | sort -u || true
if [ "${status:-0}" -ne 0 ]; then
  echo "tidy: clang-tidy found problems (full log: $build_dir/tidy.log) after ${SECONDS} s"
  exit 1
fi
echo "tidy: clean ($(grep -c -- ' -p=' "$build_dir/tidy.log") files) in ${SECONDS} s"
