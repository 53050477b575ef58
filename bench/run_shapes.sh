#!/bin/sh
# Times `aggpack shapes -n 100000` (generate + measure + CSV) with 1 and 2 threads and checks that
# both CSVs are byte-identical. Uses hyperfine (Debian package hyperfine) when installed, else
# /usr/bin/time. Figures go into bench/RESULTS.md, section "Generator".
#
#   bench/run_shapes.sh [path/to/aggpack] [extra shapes options...]
#   e.g. bench/run_shapes.sh build/aggpack -r 0.1 -L 0.05
set -eu
binary=${1:-build/aggpack}
[ $# -gt 0 ] && shift
options=${*:--r 0.1 -L 0.05 --alpha 0.5}
count=${COUNT:-100000}
runs=${RUNS:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM

echo "aggpack shapes -n $count $options  ($(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg))"
if command -v hyperfine >/dev/null 2>&1; then
  hyperfine --warmup 1 --runs "$runs" --style basic \
    -n "1 thread" "$binary shapes -n $count $options -j 1 -o $work/one.csv --force" \
    -n "2 threads" "$binary shapes -n $count $options -j 2 -o $work/two.csv --force"
else
  for threads in 1 2; do
    /usr/bin/time -f "$threads thread(s): %e s wall, %U s user, %S s sys, %M KB max RSS" \
      "$binary" shapes -n "$count" $options -j "$threads" -o "$work/t$threads.csv" --force >/dev/null
  done
  mv "$work/t1.csv" "$work/one.csv"
  mv "$work/t2.csv" "$work/two.csv"
fi
if cmp -s "$work/one.csv" "$work/two.csv"; then
  echo "CSV with 1 and 2 threads: byte-identical ($(wc -l <"$work/one.csv") lines)"
else
  echo "CSV with 1 and 2 threads: DIFFERENT" >&2
  exit 1
fi
