#!/usr/bin/env bash
# Instructions per particle and per final vertex of `aggpack shapes` (growth + describe) with two
# aggpack binaries: valgrind callgrind Ir of `-n N+1` minus `-n 1` (start-up excluded), one
# thread, alpha 0.5, R = 0.1 m, L/R 1, 0.5, 0.25, both growth rules. Load-independent.
#
#   bench/compare_shapes_cost.sh OLD_BINARY NEW_BINARY [WORKDIR]
set -euo pipefail
old=$(realpath "$1")
new=$(realpath "$2")
work=${3:-$(mktemp -d)}
mkdir -p "$work"
cd "$work"

instructions() {  # binary, count, growth, edge length -> total Ir
  valgrind --tool=callgrind --callgrind-out-file=cg.out "$1" shapes -n "$2" -j 1 --alpha 0.5 \
    --radius 0.1 --edge-length "$4" --growth "$3" >/dev/null 2>cg.log
  grep -m1 -E "^summary:|^totals:" cg.out | awk '{print $2}'
}

mean_vertices() {  # binary, count, growth, edge length -> mean final vertex count
  "$1" shapes -n "$2" -j 1 --alpha 0.5 --radius 0.1 --edge-length "$4" --growth "$3" \
    -o vertices.csv --force >/dev/null
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "vertices") c = i; next }
           { s += $c; n += 1 } END { printf "%.1f", s / n }' vertices.csv
}

printf "%-9s %5s %6s %9s %12s %12s %8s %10s %10s\n" growth "L/R" n vertices "Ir/part old" \
  "Ir/part new" change "Ir/vtx old" "Ir/vtx new"
for growth in hull midpoint; do
  for ratio in 1 0.5 0.25; do
    case $ratio in 1) n=1000 ;; 0.5) n=200 ;; *) n=40 ;; esac
    edge=$(echo "0.1 * $ratio" | bc -l)
    per() {  # binary -> Ir per particle
      local a b
      a=$(instructions "$1" $((n + 1)) "$growth" "$edge")
      b=$(instructions "$1" 1 "$growth" "$edge")
      echo "($a - $b) / $n" | bc -l
    }
    vertices=$(mean_vertices "$new" "$n" "$growth" "$edge")
    o=$(per "$old")
    w=$(per "$new")
    printf "%-9s %5s %6d %9s %12.0f %12.0f %+7.1f%% %10.0f %10.0f\n" "$growth" "$ratio" "$n" \
      "$vertices" "$o" "$w" "$(echo "($w - $o) * 100 / $o" | bc -l)" \
      "$(echo "$o / $vertices" | bc -l)" "$(echo "$w / $vertices" | bc -l)"
  done
done
