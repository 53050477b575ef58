#!/usr/bin/env bash
# Scale of particle.library (docs/shape-library.md): import time of N meshes of 20,000 triangles,
# and the memory of a lattice packing from a 200-shape library at two particle counts.
# Usage: bench/shape_library.sh AGGPACK_BINARY WORKDIR   (needs /usr/bin/python3 with numpy)
set -euo pipefail
aggpack=$(realpath "$1")
work=$2
here=$(dirname "$(realpath "$0")")
mkdir -p "$work"
cd "$work"
if [ ! -d lib1000 ]; then /usr/bin/python3 "$here/make_mesh_library.py" lib1000 1000; fi
if [ ! -d lib200 ]; then
  mkdir lib200
  for f in lib1000/rock0[01]*.stl; do ln -s "../$f" lib200/; done
fi
echo "== import: 1000 meshes x 20,000 triangles (aggpack shapes --library)"
/usr/bin/time -v "$aggpack" shapes --library lib1000 -o import.csv -f 2>import.time | tail -n 25
grep -E "Elapsed|User time|System time|Maximum resident" import.time
for sites in 20 47; do  # 20^3 = 8,000 and 47^3 = 103,823 lattice sites
  length=$(/usr/bin/python3 -c "print($sites * 0.02)")
  cat >lattice$sites.toml <<TOML
[container]
kind = "box"
length = $length
width = $length
depth = $length
[particle]
library = "lib200"
radius = 0.01
[packer]
kind = "lattice"
seed = 1
TOML
  echo "== lattice of ${sites}^3 sites from the 200-shape library"
  /usr/bin/time -v "$aggpack" pack lattice$sites.toml -o lattice$sites.h5 -f 2>lattice$sites.time \
    | grep -E "^particles|^placed|solid" || true
  grep -E "Elapsed|User time|Maximum resident" lattice$sites.time
done
