#!/usr/bin/env bash
# clang-tidy (Debian's clang-tidy 14) with the project's .clang-tidy (naming rules + cheap bugprone
# checks, warnings are errors) over every C++ file the build compiles: src/, app/ (CLI and GUI),
# python/ (the module), tests/ and bench/, and the headers they include from include/aggpack, src/,
# app/, python/ and tests/.
# Configures (does not build) build-tidy/ with every part on, for its compile_commands.json.
#
#   scripts/tidy.sh [FILE_REGEX]     e.g. scripts/tidy.sh 'src/io/' (default: all our files)
#
# A file already found clean with the same inputs -- its text, the project headers it includes,
# its compile flags, .clang-tidy and clang-tidy's version -- is not checked again: scripts/
# tidy_files.py keeps a marker per clean input set in AGGPACK_TIDY_CACHE (default
# ~/.cache/aggpack/tidy; absent = a full run). AGGPACK_TIDY_CACHE=none checks every file.
# Environment: AGGPACK_TIDY_JOBS (default 2), AGGPACK_TIDY_BUILD_DIR (default build-tidy).
# A finding that must stay gets `// NOLINT(check-name): reason` on its line.
# Files with the same compile command are checked in batches of up to 32 (AGGPACK_TIDY_BATCH):
# one clang-tidy run over a unity file that includes them, so the system headers (Eigen: ~5 s of
# clang-tidy per file) are parsed and matched once per batch; tidy_files.py says how a batch that
# is not clean is checked again file by file. Cost of a full run (264 files) on the 2-core VM:
# 1,381 s one file at a time (idle, 2026-12-05); src/io/ alone 411 -> 91 s of CPU batched.
# Each batch costs ~17 s of CPU besides ~2.2 s per file (tests/io/, 26 files, no cache: 106 s
# of CPU in batches of 12, 73 s in one batch of 26, 2026-12-05), hence batches of 32.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${AGGPACK_TIDY_BUILD_DIR:-build-tidy}
tidy=$(command -v clang-tidy-14 || command -v clang-tidy)
mkdir -p "$build_dir"
# No compiler launcher here: clang-tidy reads the compile commands as they are.
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DAGGPACK_BUILD_TESTS=ON -DAGGPACK_BUILD_BENCH=ON -DAGGPACK_CCACHE=OFF -DAGGPACK_UNITY=OFF \
  >"$build_dir/configure.log" 2>&1 || {
  cat "$build_dir/configure.log"
  exit 1
}
cache=${AGGPACK_TIDY_CACHE:-$HOME/.cache/aggpack/tidy}
cache_args=(--cache "$cache")
if [ "$cache" = none ]; then cache_args=(--no-cache); fi
SECONDS=0
status=0
python3 scripts/tidy_files.py "$build_dir" "${1:-(src|app|python|tests|bench)/}" \
  --jobs "${AGGPACK_TIDY_JOBS:-2}" --batch "${AGGPACK_TIDY_BATCH:-32}" --tidy "$tidy" \
  --clang "$(command -v clang++-14 || command -v clang++)" "${cache_args[@]}" || status=$?
echo "tidy: ${SECONDS} s"
exit $status
