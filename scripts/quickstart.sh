#!/usr/bin/env bash
# Fresh Debian bookworm, as root: install dependencies, build, and run the main job on the
# built-in default -- the paper's case (lattice packing, alpha 0.5, R 0.1 m, L 0.1 m) -- then
# export it and render a picture. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
mkdir -p out
./build/aggpack pack -o out/paper.h5 --force
./build/aggpack info out/paper.h5
for format in stl dat inp vtu; do
  ./build/aggpack export out/paper.h5 --format "$format" -o "out/paper.$format" --force
done
if ./build/aggpack render --help >/dev/null 2>&1; then
  ./build/aggpack render out/paper.h5 -o out/paper.png --force
fi
echo "quickstart: outputs in $(pwd)/out"
