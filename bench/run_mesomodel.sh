#!/usr/bin/env bash
# Whole-program mesomodel benchmark (issue 16, item 5): packs the 100 mm cube
# (examples/mesomodel-cube.toml) and the 150 x 300 mm cylinder (examples/mesomodel-cylinder.toml),
# then meshes each with a 0.1 mm ITZ, as a solid layer (.vtu) and as cohesive elements (.inp); logs wall/CPU time and peak memory of every step and the
# mesomodel's report (element counts, volumes, quality per phase).
#
#   bench/run_mesomodel.sh [AGGPACK] [OUT_DIR] [ITZ_M]
#
# AGGPACK defaults to build/aggpack, OUT_DIR to bench-mesomodel/, ITZ_M to 0.0001. Figures in
# bench/RESULTS.md come from this script; say there whether the machine was idle (`uptime` is
# logged). The cube's packing takes ~4 minutes, the cylinder's mesh ~5 GB of memory.
set -euo pipefail

aggpack=$(realpath "${1:-build/aggpack}")
out=${2:-bench-mesomodel}
itz=${3:-0.0001}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
cd "$out"
log=summary.txt
{
  echo "# $(date -u +%FT%TZ) $(uname -n) $(nproc) cores; $(uptime)"
  echo "# $("$aggpack" --version 2>/dev/null || true), ITZ $itz m"
} >"$log"

timed() {  # timed LABEL COMMAND...: runs it, appends its output and time/memory to the log
  local label=$1
  shift
  echo "## $label: $*" >>"$log"
  /usr/bin/time -f "$label: %e s wall, %U s user, %M KB peak" "$@" >>"$log" 2>&1
}

for case in cube cylinder; do
  timed "pack $case" "$aggpack" pack "$here/examples/mesomodel-$case.toml" -o "$case.h5" \
    --progress none --force
  timed "mesomodel $case" "$aggpack" mesomodel "$case.h5" --itz "$itz" -o "$case.vtu" --force
  # The cohesive ITZ of the same packing: bonded mesh, split, one COH3D6 per surface triangle.
  timed "mesomodel $case cohesive" "$aggpack" mesomodel "$case.h5" --itz "$itz" \
    --itz-kind cohesive -o "$case-cohesive.inp" --force
done
grep -E "^## |wall,|^(mesomodel|mesh|phase|AGGREGATE|ITZ|MORTAR|cohesive ITZ|solid fraction|particles) " "$log"
