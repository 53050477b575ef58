#!/usr/bin/env bash
# Instruction counts (valgrind callgrind, Ir) of whole-program runs with two aggpack binaries, for
# refactorings that must not make anything slower. Instruction counts do not depend on the machine's
# load, unlike wall times on a shared 2-core VM; they do not see memory stalls, so pair them with
# the Google Benchmark figures when a change touches data layout.
#
#   bench/compare_cost.sh OLD_BINARY NEW_BINARY [WORKDIR]
#
# Prints one line per command: Ir old, Ir new, change in %.
set -euo pipefail
old=$(realpath "$1")
new=$(realpath "$2")
work=${3:-$(mktemp -d)}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$work"
cd "$work"

# Inputs made once with the old binary, so both binaries read the same files.
"$old" pack -o paper.h5 --force >/dev/null 2>&1
"$old" pack "$root/examples/triaxial-cylinder.toml" -o cyl.h5 --force >/dev/null 2>&1

commands=(
  "pack -o out-paper.h5 --force"
  "pack $root/examples/concrete-fuller.toml -o out-cf.h5 --force"
  "pack $root/examples/triaxial-cylinder.toml -o out-cyl.h5 --force"
  "info paper.h5"
  "export paper.h5 -o out.inp --force"
  "export paper.h5 -o out10.inp --quadratic --force"
  "export cyl.h5 -o out.stl --force"
  "export cyl.h5 -o out.vtu --force"
  "export paper.h5 -o out.dat --force"
)

instructions() {  # binary, command... -> total Ir
  local binary=$1
  shift
  valgrind --tool=callgrind --callgrind-out-file=cg.out "$binary" "$@" >/dev/null 2>cg.log
  grep -m1 -E "^summary:|^totals:" cg.out | awk '{print $2}'
}

printf "%-60s %15s %15s %8s\n" command "Ir old" "Ir new" change
for command in "${commands[@]}"; do
  # shellcheck disable=SC2086
  a=$(instructions "$old" $command)
  # shellcheck disable=SC2086
  b=$(instructions "$new" $command)
  printf "%-60s %15s %15s %+7.2f%%\n" "${command//$root\//}" "$a" "$b" \
    "$(echo "($b - $a) * 100 / $a" | bc -l)"
done
