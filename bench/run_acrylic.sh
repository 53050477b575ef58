#!/usr/bin/env bash
# The paper's acrylic experiment (issue 15, item 3): a seed ensemble of the angle-of-repose test
# for each of the two shape-matched acrylic particles (examples/repose-acrylic-075.toml and
# -048.toml, one contact parameter set), a Welch test of their difference, and the reduced sweep
# of the paper's trends (examples/sweep-acrylic-trends.toml, an ensemble per case). A long run
# (about 1-2 CPU hours), not a CI test; figures in bench/RESULTS.md come from it.
#
#   bench/run_acrylic.sh [AGGPACK] [OUT_DIR] [SEEDS] [SWEEP_SEEDS] [THREADS]
#
# Defaults: build/aggpack, bench-acrylic/, seeds 1-24, sweep seeds 1-4 ("none": no sweep), all
# cores. Outputs:
# OUT/p1/ and OUT/p2/ (ensemble.json|csv|png and seed-<k>/), OUT/sweep/ (sweep.csv|png),
# OUT/summary.txt (machine, load, times, both means with 95 % intervals, the difference test).
set -euo pipefail

aggpack=$(realpath "${1:-build/aggpack}")
out=${2:-bench-acrylic}
seeds=${3:-1-24}
sweep_seeds=${4:-1-4}
threads=${5:-0}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
log="$out/summary.txt"
{
  echo "# $(date -u +%FT%TZ) $(uname -n) $(nproc) cores; $(uptime)"
  echo "# $("$aggpack" --version 2>/dev/null || true); seeds $seeds, sweep seeds $sweep_seeds"
} >"$log"

run() {  # run NAME COMMAND...: time a command, log wall/CPU/peak memory
  local name=$1
  shift
  /usr/bin/time -f "$name: %e s wall, %U s user, %M KB peak" -a -o "$log" "$@" \
    >"$out/$name.log" 2>&1
}

run p1 "$aggpack" repose "$here/examples/repose-acrylic-075.toml" --seeds "$seeds" -j "$threads" \
  -o "$out/p1" -f --progress none
run p2 "$aggpack" repose "$here/examples/repose-acrylic-048.toml" --seeds "$seeds" -j "$threads" \
  -o "$out/p2" -f --progress none

# Both means with their intervals, and Welch's t-test of the difference (two-sided, 5 %).
python3 - "$out/p1/ensemble.json" "$out/p2/ensemble.json" >>"$log" <<'PY'
import json, math, sys
def load(path):
    data = json.load(open(path))
    angles = [s["angle_degrees"] for s in data["seeds"] if s.get("valid", s.get("is_valid", True))]
    return angles
def t_quantile(df):  # two-sided 95 % Student-t quantile, by bisection on the CDF
    from math import lgamma, exp, pi, sqrt
    def pdf(x):
        return exp(lgamma((df + 1) / 2) - lgamma(df / 2)) / sqrt(df * pi) * (1 + x * x / df) ** (-(df + 1) / 2)
    def cdf(x, n=4000):
        h = x / n
        return 0.5 + sum(pdf((i + 0.5) * h) for i in range(n)) * h
    lo, hi = 0.0, 50.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cdf(mid) < 0.975 else (lo, mid)
    return 0.5 * (lo + hi)
p = [load(a) for a in sys.argv[1:3]]
stats = []
for name, a in zip(("particle 1 (075)", "particle 2 (048)"), p):
    n = len(a)
    m = sum(a) / n
    sd = math.sqrt(sum((x - m) ** 2 for x in a) / (n - 1))
    h = t_quantile(n - 1) * sd / math.sqrt(n)
    stats.append((n, m, sd))
    print(f"{name}: n {n}, mean {m:.2f} deg, sd {sd:.2f}, 95% CI [{m - h:.2f}, {m + h:.2f}] (half-width {h:.2f})")
(n1, m1, s1), (n2, m2, s2) = stats
se = math.sqrt(s1 * s1 / n1 + s2 * s2 / n2)
df = (s1 * s1 / n1 + s2 * s2 / n2) ** 2 / ((s1 * s1 / n1) ** 2 / (n1 - 1) + (s2 * s2 / n2) ** 2 / (n2 - 1))
t = (m1 - m2) / se
q = t_quantile(df)
print(f"difference p1 - p2: {m1 - m2:.2f} deg, 95% CI [{m1 - m2 - q * se:.2f}, {m1 - m2 + q * se:.2f}], "
      f"Welch t {t:.2f} on {df:.1f} df: {'significant' if abs(t) > q else 'not significant'} at 5%")
PY

[ "$sweep_seeds" = none ] || run sweep "$aggpack" sweep "$here/examples/sweep-acrylic-trends.toml" --seeds "$sweep_seeds" \
  -j "$threads" -o "$out/sweep" -f --progress none
echo "# done $(date -u +%FT%TZ); $(uptime)" >>"$log"
cat "$log"
