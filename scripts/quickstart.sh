#!/usr/bin/env bash
# Fresh Debian bookworm, as root: install dependencies, build, and run the main job on the
# built-in default -- the paper's case (lattice packing, alpha 0.5, R 0.1 m, L 0.1 m) -- then
# export it and render a picture. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
echo "quickstart: installing Debian packages (about 1-2 minutes), then building (about 9 minutes"
echo "on 2 cores; scripts/test.sh reuses this build)"
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
./build/aggpack pack -o out/paper.h5 --force
./build/aggpack info out/paper.h5
for format in stl dat inp vtu; do
  ./build/aggpack export out/paper.h5 --format "$format" -o "out/paper.$format" --force
done
# The paper's trough-test deck run by CalculiX as written: the whole model (1,050 particles, walls,
# baffle, contact pairs, gravity) for a few microseconds of simulated time; the full 8.5 s needs
# ~2.4e7 explicit increments in ccx (docs/export.md, "Complete decks"). The deck is made from aggpack 0.1's
# particles (particle.growth = midpoint, as the deck tests do): ccx sets up its contact structure
# for those in about 10 s of CPU, while the default hull rule's particles (more, smaller surface
# facets) kept it in that set-up for over 3 CPU-minutes (20 minutes on a loaded machine); the
# number of increments (about a dozen here) does not matter next to it.
echo "quickstart: CalculiX on the paper's trough deck (about 10-30 s)"
./build/aggpack pack --set particle.growth=midpoint -o out/paper-midpoint.h5 --force --progress none \
  >/dev/null
./build/aggpack export out/paper-midpoint.h5 --deck calculix --settle-time 2e-6 \
  --trough-length 3.0001 --baffle-speed 100 --rest-time 0 -o out/paper-trough.inp --force
(cd out && ccx -i paper-trough >paper-trough.ccx.log 2>&1) || {
  echo "quickstart: ccx failed on out/paper-trough.inp (log: out/paper-trough.ccx.log)" >&2
  exit 1
}
if grep -q -i -e '\*ERROR' -e '\*WARNING' out/paper-trough.ccx.log; then
  echo "quickstart: ccx reported an error or warning (out/paper-trough.ccx.log)" >&2
  exit 1
fi
echo "quickstart: CalculiX ran the paper's trough deck (out/paper-trough.ccx.log)"
if ./build/aggpack render --help >/dev/null 2>&1; then
  ./build/aggpack render out/paper.h5 -o out/paper.png --force
fi
echo "quickstart: outputs in $(pwd)/out"
