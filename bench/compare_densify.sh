#!/usr/bin/env bash
# Paired densify runs, two binaries side by side on the same start packing, for a machine that
# is not idle: both run at once (niced, one thread each, so they share the load alike) for the
# same sweep budget, and their fraction is recorded against CPU time, the fair clock when other
# jobs take an unknown share of the cores (an idle 2-core machine at -j 0 gives about half the
# CPU time as wall time).
#
#   bench/compare_densify.sh OLD NEW START.h5 SWEEPS PREFIX [densify options...]
#
# Writes PREFIX-old.* and PREFIX-new.* (.h5, .out, .time: /usr/bin/time -v, .trace: the
# densify trace, .curve: "cpu_seconds sweeps solid_fraction", the trace with the process's CPU
# time sampled from /proc every second and joined on wall time) and prints one summary line per
# binary: final fraction, verification, sweeps, CPU, wall, peak memory, and the CPU seconds at
# which the fraction first reached 0.50, 0.55, 0.58, 0.60, 0.62, 0.64.
set -euo pipefail
[ $# -ge 5 ] || { sed -n 2,14p "$0"; exit 2; }
old=$(realpath "$1")
new=$(realpath "$2")
start=$3
sweeps=$4
prefix=$5
shift 5

launch() {  # launch TAG BINARY ARGS...: background run, sampler
  local tag=$1 binary=$2
  shift 2
  /usr/bin/time -v nice -n 10 "$binary" densify "$start" -o "$prefix-$tag.h5" -f --progress none \
    -j 1 --sweeps "$sweeps" --trace "$prefix-$tag.trace" "$@" \
    >"$prefix-$tag.out" 2>"$prefix-$tag.time" &
}
launch old "$old" "$@"
old_pid=$!
launch new "$new" "$@"
new_pid=$!
began=$(date +%s.%N)
: >"$prefix-old.cpu"
: >"$prefix-new.cpu"
tick=$(getconf CLK_TCK)
# Sample "wall cpu" of each densify process (the child of time and nice) once a second.
sample() {
  local tag=$1 parent=$2 child
  child=$(pgrep -P "$parent" | head -n 1 || true)
  [ -n "$child" ] || return 0
  [ -r "/proc/$child/stat" ] || return 0
  awk -v now="$(date +%s.%N)" -v began="$began" -v tick="$tick" \
    '{ sub(/^.*\) /, ""); printf "%.2f %.2f\n", now - began, ($12 + $13) / tick }' \
    "/proc/$child/stat" >>"$prefix-$tag.cpu" 2>/dev/null || true
}
while kill -0 "$old_pid" 2>/dev/null || kill -0 "$new_pid" 2>/dev/null; do
  sample old "$old_pid"
  sample new "$new_pid"
  sleep 1
done
wait "$old_pid" "$new_pid" || true

for tag in old new; do
  # Join: CPU at each trace line's wall time (linear between samples; the trace clock starts
  # after loading the start packing, so its times are shifted by up to that load time).
  awk 'NR == FNR { w[n] = $1; c[n] = $2; ++n; next }
       /^#/ { next }
       { t = $1; k = 0; while (k < n - 1 && w[k + 1] < t) ++k;
         cpu = c[k];
         if (k < n - 1 && w[k + 1] > w[k]) cpu = c[k] + (c[k + 1] - c[k]) * (t - w[k]) / (w[k + 1] - w[k]);
         printf "%.2f %s %s\n", cpu, $2, $3 }' \
    "$prefix-$tag.cpu" "$prefix-$tag.trace" >"$prefix-$tag.curve"
  reached=$(awk 'BEGIN { split("0.50 0.55 0.58 0.60 0.62 0.64", f, " ") }
       { for (i = 1; i <= 6; ++i) if (!(i in at) && $3 >= f[i]) at[i] = $1 }
       END { for (i = 1; i <= 6; ++i) printf "%s@%s ", f[i], (i in at) ? at[i] "s" : "-" }' \
    "$prefix-$tag.curve")
  printf '%s: %s | %s | %s | user %s s, wall %s, peak %s kB | CPU to reach: %s\n' "$tag" \
    "$(grep -m1 'solid fraction' "$prefix-$tag.out" | tr -s ' ')" \
    "$(grep -m1 'verified' "$prefix-$tag.out" | tr -s ' ')" \
    "$(grep -m1 -E '^(fixed|bed):' "$prefix-$tag.out")" \
    "$(awk -F': ' '/User time/ { print $2 }' "$prefix-$tag.time")" \
    "$(awk -F': ' '/Elapsed/ { print $2 }' "$prefix-$tag.time")" \
    "$(awk -F': ' '/Maximum resident/ { print $2 }' "$prefix-$tag.time")" "$reached"
done
