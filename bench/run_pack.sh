#!/bin/sh
# Runs the packing benchmarks (bench/pack_bench.cpp) one at a time under /usr/bin/time, so each
# line shows wall time, CPU time (user + sys, both cores) and peak memory next to Google
# Benchmark's counters (placed, solid_fraction, attempts, shape_s, place_s). Every random packing
# is verified (grid + exact GJK) after timing. Figures go into bench/RESULTS.md, section
# "Packing".
#
#   bench/run_pack.sh [path/to/pack_bench] [benchmark regex]
#   e.g. bench/run_pack.sh build/bench/pack_bench 'Lattice|100k|Scaling'
set -eu
binary=${1:-build/bench/pack_bench}
filter=${2:-.}
echo "pack_bench ($(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg))"
for name in $("$binary" --benchmark_list_tests | grep -E "$filter"); do
  /usr/bin/time -f "  -> %e s wall, %U s user, %S s sys, %M KB max RSS" \
    "$binary" --benchmark_filter="^${name}\$" --benchmark_counters_tabular=false 2>&1 |
    grep -E "^(BM_|  placed|  ->)" || true
  echo "   (load: $(cut -d' ' -f1-3 /proc/loadavg))"
done
