#!/usr/bin/env bash
# The shape effect on the angle of repose: seed ensembles of the trough test for four particle
# shapes from rounded (V / V_circ 0.80) to flaky and angular (V / V_circ 0.35 with flatness 0.5),
# each found by `aggpack calibrate` at a 10 mm enclosing diameter and L = R, in the acrylic trough
# of examples/repose-acrylic-075.toml (mu_s 0.24, the same contacts for every shape: nothing is
# fitted per shape), plus both acrylic examples' own ensembles. Writes each angle, the means with
# 95 % intervals, Welch's test between the two extreme shapes and a plot. A long run (each test
# takes 1-3 CPU minutes: about 4 CPU hours for 6 x 16 runs), not a CI test; figures in
# bench/RESULTS.md come from it.
#
#   bench/run_shape_effect.sh [AGGPACK] [OUT_DIR] [SEEDS] [THREADS]
#
# Defaults: build/aggpack, bench-shape-effect/, seeds 1-16, all cores. Seeds run in chunks of four
# over every case in turn, so a run stopped early still has a balanced share of every case;
# rerunning skips the chunks already done. Summary only: bench/run_shape_effect.sh AGGPACK OUT
# summary.
set -euo pipefail

aggpack=$(realpath "${1:-build/aggpack}")
out=${2:-bench-shape-effect}
seeds=${3:-1-16}
threads=${4:-0}
here=$(cd "$(dirname "$0")/.." && pwd)
trough="$here/examples/repose-acrylic-075.toml"
mkdir -p "$out"
log="$out/summary.txt"

# name | calibrate targets (10 mm enclosing diameter, L = R)
shapes=(
  "rounded|--volume-ratio 0.80"
  "medium|--volume-ratio 0.65"
  "lean|--volume-ratio 0.50"
  "flaky-angular|--volume-ratio 0.35 --flatness 0.5"
)

if [ "$seeds" != summary ]; then
  {
    echo "# $(date -u +%FT%TZ) $(uname -n) $(nproc) cores; $(uptime)"
    echo "# $("$aggpack" --version 2>/dev/null || true); seeds $seeds"
  } >>"$log"
  declare -A settings
  for entry in "${shapes[@]}"; do
    name=${entry%%|*}
    targets=${entry#*|}
    # shellcheck disable=SC2086  # the targets are several flags
    "$aggpack" calibrate $targets --diameter 0.010 --edge-ratio 1 >"$out/$name-calibrate.txt"
    set_flags=""
    for key in alpha radius edge_length elongation flatness growth min_edge_ratio; do
      value=$(grep -E "^$key = " "$out/$name-calibrate.txt" | head -1 | cut -d' ' -f3 | tr -d '"')
      set_flags+=" --set particles.$key=$value"
    done
    settings[$name]=$set_flags
    echo "# $name: $(grep -E '^(found|achieved)' "$out/$name-calibrate.txt" | tr '\n' ' ')" >>"$log"
  done
  first=${seeds%-*}
  last=${seeds#*-}
  for ((begin = first; begin <= last; begin += 4)); do
    end=$((begin + 3 > last ? last : begin + 3))
    chunk="$begin-$end"
    for entry in "${shapes[@]}" "acrylic-075|" "acrylic-048|"; do
      name=${entry%%|*}
      dir="$out/$name/seeds-$chunk"
      [ -f "$dir/ensemble.json" ] && continue
      mkdir -p "$out/$name"
      case $name in
        acrylic-075) config=$here/examples/repose-acrylic-075.toml flags="" ;;
        acrylic-048) config=$here/examples/repose-acrylic-048.toml flags="" ;;
        *) config=$trough flags=${settings[$name]} ;;
      esac
      # shellcheck disable=SC2086
      /usr/bin/time -f "$name seeds $chunk: %e s wall, %U s user, %M KB peak" -a -o "$log" \
        "$aggpack" repose "$config" $flags --seeds "$chunk" -j "$threads" -o "$dir" -f \
        --progress none >"$dir.log" 2>&1 || echo "$name seeds $chunk: failed (see $dir.log)" >>"$log"
    done
  done
fi

# Every seed's angle per case, the means with 95 % intervals, Welch's test of the extremes, a plot.
/usr/bin/python3 - "$out" >>"$log" <<'PY'  # Debian's, with python3-scipy
import glob, json, math, os, sys
from scipy import stats
out = sys.argv[1]
cases = ["rounded", "medium", "lean", "flaky-angular", "acrylic-075", "acrylic-048"]
data = {}
for case in cases:
    angles, ratio = [], None
    for path in sorted(glob.glob(os.path.join(out, case, "seeds-*", "seed-*", "repose.json"))):
        run = json.load(open(path))
        if run["fit"].get("valid", False):
            angles.append(run["fit"]["angle_degrees"])
    calib = os.path.join(out, case + "-calibrate.txt")
    if os.path.exists(calib):
        for line in open(calib):
            if line.startswith("achieved") and "volume_ratio" in line:
                ratio = float(line.split("=")[1].split()[0])
    if angles:
        data[case] = (angles, ratio)
print("case, n, mean angle (deg), 95 % CI, sd, V/V_circ")
for case, (angles, ratio) in data.items():
    n = len(angles)
    mean = sum(angles) / n
    sd = stats.tstd(angles) if n > 1 else float("nan")
    half = stats.t.ppf(0.975, n - 1) * sd / math.sqrt(n) if n > 1 else float("nan")
    print(f"{case}, {n}, {mean:.2f}, [{mean - half:.2f}, {mean + half:.2f}], {sd:.2f}, "
          f"{ratio if ratio is not None else '-'}")
if "rounded" in data and "flaky-angular" in data and min(len(data[c][0]) for c in ("rounded", "flaky-angular")) > 1:
    a, b = data["flaky-angular"][0], data["rounded"][0]
    t, p = stats.ttest_ind(a, b, equal_var=False)
    print(f"Welch flaky-angular - rounded: difference {sum(a)/len(a) - sum(b)/len(b):.2f} deg, "
          f"t = {t:.2f}, p = {p:.3g}")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for case, (angles, ratio) in data.items():
        if ratio is None or len(angles) < 2:
            continue
        mean = sum(angles) / len(angles)
        half = stats.t.ppf(0.975, len(angles) - 1) * stats.tstd(angles) / math.sqrt(len(angles))
        ax.errorbar([ratio], [mean], yerr=[half], fmt="o", capsize=4, label=f"{case} (n={len(angles)})")
        ax.plot([ratio] * len(angles), angles, ".", color="grey", alpha=0.5)
    ax.set_xlabel("V / V_circ of the particles (calibrated mean)")
    ax.set_ylabel("angle of repose (deg)")
    ax.set_title("Shape effect at the acrylic trough, mu_s 0.24 (mean, 95 % CI; dots: seeds)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "shape_effect.png"), dpi=110)
except Exception as error:  # the numbers above stand without the picture
    print("plot skipped:", error)
PY
cat "$log"
