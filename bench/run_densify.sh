#!/usr/bin/env bash
# Whole-program densify benchmark (issue 14's targets): builds the start packings by random
# sequential addition, densifies each for a wall-time budget, and records time, peak memory, the
# final fraction, the final exact verification and a fraction-vs-time trace per run; then plots
# the traces (docs/images/densify-fraction-vs-time.png, needs gnuplot).
#
#   bench/run_densify.sh [AGGPACK] [OUT_DIR] [SCALE]
#
# AGGPACK defaults to build/aggpack, OUT_DIR to bench-densify/. SCALE (default 1) multiplies
# every time budget (e.g. 0.1 for a quick check). Figures in bench/RESULTS.md come from this
# script; say there whether the machine was idle (`uptime` is logged).
set -euo pipefail

aggpack=${1:-build/aggpack}
out=${2:-bench-densify}
scale=${3:-1}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
aggpack=$(realpath "$aggpack")
plot_dir=$(realpath "$out")
cd "$out"
log=summary.txt
: >"$log"
{
  echo "# $(date -u +%FT%TZ) $(uname -n) $(nproc) cores; $(uptime)"
  echo "# $("$aggpack" --version 2>/dev/null || true)"
} >>"$log"

# config NAME EDGE FILL SIZES: a random-packing config in a cube of EDGE m filled to FILL, alpha
# 0.5, L = r; SIZES is the size block (single size or a grading).
config() {
  cat >"$1.toml" <<EOF
[container]
kind = "box"
length = $2
width = $2
depth = $2
[particle]
alpha = 0.5
edge_length = 0.0
edge_length_ratio = 1.0
$4
[packer]
kind = "random"
seed = 1
target_fraction = $3
gap = 0.0
EOF
}
single_size='radius = 0.01'  # r = 10 mm
# Fuller d 5-20 mm (d_max/d_min = 4), q = 0.5.
fuller_grading='[grading]
kind = "fuller"
size_min = 0.005
size_max = 0.02
exponent = 0.5'

config single-10k 0.302 0.33 "$single_size"
config single-100k 0.672 0.33 "$single_size"
config fuller-10k 0.12 0.45 "$fuller_grading"
for start in single-10k single-100k fuller-10k; do
  [ -f "$start.h5" ] || "$aggpack" pack "$start.toml" -o "$start.h5" --progress none >/dev/null
done
# The paper's particles (alpha 0.5, R = 0.1 m, L = 0.1 m), 1,050 asked in a 1 x 1 x 3.5 m box.
cat >paper.toml <<EOF
[container]
kind = "box"
length = 1.0
width = 1.0
depth = 3.5
[particle]
alpha = 0.5
radius = 0.1
edge_length = 0.1
[packer]
kind = "random"
seed = 1
target_count = 1050
gap = 0.0
EOF
[ -f paper.h5 ] || "$aggpack" pack paper.toml -o paper.h5 --progress none >/dev/null

# run NAME SECONDS START ARGS...: one densify run with -j 0 (all cores).
run() {
  local name=$1 seconds=$2 start=$3
  shift 3
  local budget
  budget=$(awk -v s="$seconds" -v k="$scale" 'BEGIN { printf "%g", s * k }')
  /usr/bin/time -v "$aggpack" densify "$start.h5" -o "$name.h5" -f --progress none -j 0 \
    --sweeps 1000000 --max-time "$budget" --trace "$name.trace" "$@" >"$name.out" 2>"$name.time"
  {
    echo "## $name: aggpack densify $start.h5 -o $name.h5 --sweeps 1000000 --max-time $budget $*"
    grep -E "^(fixed|bed):|verified|solid fraction|bulk" "$name.out" || true
    grep -E "Elapsed|User time|Maximum resident" "$name.time"
  } >>"$log"
}

run single-10k-30s 30 single-10k --target-fraction 0.64
run single-10k-300s 300 single-10k --target-fraction 0.64
run single-100k-180s 180 single-100k --target-fraction 0.64
run single-100k-900s 900 single-100k --target-fraction 0.64
run fuller-10k-300s 300 fuller-10k --target-fraction 0.75
run bed-paper-60s 60 paper --mode bed
cat "$log"
if command -v gnuplot >/dev/null; then
  (cd "$here" && gnuplot -e "dir='$plot_dir'" bench/densify_plot.gp)
fi
