#!/usr/bin/env bash
# Fuzzing (issue 12): builds the libFuzzer targets of tests/fuzz with clang + ASan + UBSan into
# build-fuzz/ and runs each for SECONDS (default 90; the long run: scripts/fuzz.sh 3600), the
# targets side by side, one core each (AGGPACK_FUZZ_JOBS=1: one after the other).
#   scripts/fuzz.sh [SECONDS] [extra cmake arguments...]
#   AGGPACK_FUZZ_TARGETS="native_reader"  run only some targets (default: all)
#   AGGPACK_FUZZ_IGNORE="timeout"  report these kinds of finding without failing (default: none)
# Targets: native_reader (the .h5 reader), config_reader (pack TOML + --set), repose_config (the
# repose / sweep TOML + --set; needs Bullet, as the simulation module does).
# Seeds (read only): tests/io/fixtures/bad-inputs/ (the native files and configs of issue 12),
# examples/*.toml and tests/fuzz/corpus/<target>/ (TOML + --set strings); new inputs go to
# build-fuzz/corpus/<target>/.
# Findings (crash-*, leak-*, oom-*, timeout-*, slow-unit-*) are saved in build-fuzz/artifacts/
# <target>/ and make the script fail; reproduce one with build-fuzz/tests/fuzz/fuzz_<target> FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-90}
shift || true
targets=${AGGPACK_FUZZ_TARGETS:-native_reader config_reader repose_config mesh_reader}
build=build-fuzz
# -O1 -g1 (as the sanitized build) instead of RelWithDebInfo's -O2 -g: 12 % less compile time
# (src/io's first unity batch: 16.2 vs 18.4 s of CPU, 2026-12-05), and line tables are all a
# finding's stack trace needs.
CC=${CC_FUZZ:-clang-14} CXX=${CXX_FUZZ:-clang++-14} cmake -S . -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DAGGPACK_BUILD_FUZZ=ON -DAGGPACK_BUILD_TESTS=OFF \
  -DAGGPACK_BUILD_BENCH=OFF -DAGGPACK_BUILD_GUI=OFF -DAGGPACK_BUILD_RENDER=OFF \
  -DAGGPACK_BUILD_SIM=ON -DAGGPACK_BUILD_PYTHON=OFF "$@" >/dev/null
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' $targets)

# max_len: the native seeds are up to ~24 KB; a config is a few hundred bytes. malloc_limit_mb:
# reading a file of at most 64 KB must never need a 256 MB block (issue 12: memory within a
# small multiple of the file size).
declare -A max_len=([native_reader]=65536 [config_reader]=8192 [repose_config]=8192
  [mesh_reader]=65536)
declare -A seeds=([native_reader]="tests/io/fixtures/bad-inputs"
  [config_reader]="tests/fuzz/corpus/config_reader examples tests/io/fixtures/bad-inputs"
  [repose_config]="tests/fuzz/corpus/repose_config examples"
  [mesh_reader]="tests/fuzz/corpus/mesh_reader")
# Leaks inside Debian's HDF5 on corrupted headers are not ours: tests/fuzz/lsan-suppressions.txt.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/fuzz/lsan-suppressions.txt}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
# The targets fuzz at the same time, one job each (AGGPACK_FUZZ_JOBS, default: the number of cores;
# 1 runs them one after the other): each gets its SECONDS on a core of its own, so on 2 cores the
# two targets take SECONDS of wall time instead of twice that.
parallel=${AGGPACK_FUZZ_JOBS:-$(nproc)}
running=0
trap 'kill $(jobs -p) 2>/dev/null || true' EXIT
for target in $targets; do
  corpus=$build/corpus/$target
  artifacts=$build/artifacts/$target
  mkdir -p "$corpus" "$artifacts"
  log=$build/fuzz_$target.log
  echo "fuzz: $target for $seconds s (log $log)"
  # Fork mode keeps going after an out-of-memory or timeout input and saves each finding.
  "$build/tests/fuzz/fuzz_$target" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=256 -max_len="${max_len[$target]}" \
    -artifact_prefix="$artifacts/" -print_final_stats=1 \
    "$corpus" ${seeds[$target]} >"$log" 2>&1 &
  running=$((running + 1))
  if [ "$running" -ge "$parallel" ]; then
    wait || true
    running=0
  fi
done
wait || true
for target in $targets; do
  artifacts=$build/artifacts/$target
  log=$build/fuzz_$target.log
  runs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  found=$(find "$artifacts" -type f | wc -l)
  echo "fuzz: $target: ${runs:-0} executions, $found finding(s) in $artifacts"
  for file in $(find "$artifacts" -type f | sort | head -20); do
    kind=$(basename "$file" | cut -d- -f1)
    if [[ " ${AGGPACK_FUZZ_IGNORE:-} " == *" $kind "* ]]; then
      echo "  $file (ignored: AGGPACK_FUZZ_IGNORE)"
    else
      echo "  $file"
      status=1
    fi
  done
done
exit $status
