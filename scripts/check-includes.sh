#!/usr/bin/env bash
# Fails when a module includes a module to its right in the layer table below (docs/architecture.md,
# "Layers"). Checks every #include "aggpack/<module>/..." (and <aggpack/...>, and "../<module>/...")
# in include/aggpack/<module>/, src/<module>/ and app/. Tests and benchmarks may include anything.
#
#   scripts/check-includes.sh [ROOT]     check the tree at ROOT (default: this checkout)
#   scripts/check-includes.sh --self-test
#       copies the tree to a temporary folder, checks that the copy passes, then plants one bad
#       include of each kind (a lower module including a higher one, a sibling including a sibling,
#       an unlisted module folder) and checks that each one fails.
set -euo pipefail

# ---- the layer table: a module may include only modules with a SMALLER rank (and itself). ------
# Modules on one rank are siblings and may not include each other. A folder under include/aggpack/
# or src/ that is not listed here fails the check: add a new module here first.
layers='
  0 core
  1 geom
  2 shape
  3 pack
  4 mesh
  5 io
  5 sim
  5 render
  6 config
  7 pipeline
  8 study
  9 app
'
# ------------------------------------------------------------------------------------------------

check_tree() {  # check_tree ROOT -> prints one line per violation; returns 1 if any
  local root=$1 folder
  local -a folders=()
  for folder in "$root"/include/aggpack/*/ "$root"/src/*/; do
    [ -d "$folder" ] && folders+=("${folder%/}")
  done
  [ -d "$root/app" ] && folders+=("$root/app")
  # One awk pass: the table, then "FOLDER<tab>file:line:text" for every include of a module.
  local folder_list
  folder_list=$(printf '%s\n' "${folders[@]}")
  {
    while IFS= read -r folder; do
      printf 'folder\t%s\n' "$folder"
      grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*["<](aggpack/|\.\./)[A-Za-z0-9_]+/' \
        --include='*.h' --include='*.hpp' --include='*.cpp' --include='*.cc' "$folder" |
        sed 's/^/include\t/' || true
    done <<<"$folder_list"
  } | awk -v root="$root/" -v table="$layers" '
    BEGIN {
      FS = "\t"
      n = split(table, lines, "\n")
      for (i = 1; i <= n; i++) if (split(lines[i], f, " ") == 2) rank[f[2]] = f[1]
      failures = 0
    }
    function short(path) { return index(path, root) == 1 ? substr(path, length(root) + 1) : path }
    $1 == "folder" {
      module = $2; sub(/.*\//, "", module)
      if (!(module in rank)) {
        print "check-includes: " short($2) "/ is not in the layer table (scripts/check-includes.sh)"
        failures = 1
      }
      next
    }
    $1 == "include" && (module in rank) {
      line = $2
      file = line; sub(/:.*/, "", file)
      text = line; sub(/^[^:]*:[0-9]+:/, "", text)
      target = text
      sub(/^[^"<]*["<](aggpack\/|\.\.\/)/, "", target); sub(/\/.*/, "", target)
      if (target == module) next
      if (!(target in rank) || rank[target] + 0 >= rank[module] + 0) {
        print "check-includes: " short(file) " (" module ", layer " rank[module] ") includes " \
              target " (layer " ((target in rank) ? rank[target] : "unlisted") "): " text
        failures = 1
      }
    }
    END { exit failures }'
}

self_test() {
  local source_root=$1 scratch
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' RETURN
  mkdir -p "$scratch/clean"
  for folder in include src app; do
    [ -d "$source_root/$folder" ] && cp -r "$source_root/$folder" "$scratch/clean/"
  done
  if ! check_tree "$scratch/clean" >/dev/null; then
    echo "check-includes self-test: the unmodified tree already fails"; return 1
  fi
  local -a cases=(
    "lower includes higher|src/core/self_test_bad.cpp|#include \"aggpack/pack/packing.h\""
    "header includes app-level module|include/aggpack/geom/self_test_bad.h|#include \"aggpack/pipeline/pipeline.h\""
    "relative include of a higher module|src/pack/self_test_bad.cpp|#include \"../io/export_detail.h\""
    "sibling includes sibling|src/sim/self_test_bad.cpp|#include \"aggpack/io/native.h\""
    "angle-bracket include|src/mesh/self_test_bad.cpp|#include <aggpack/render/renderer.h>"
    "unlisted module folder|src/extra/self_test.cpp|#include \"aggpack/core/error.h\""
  )
  local entry name file text failed=0
  for entry in "${cases[@]}"; do
    IFS='|' read -r name file text <<<"$entry"
    rm -rf "$scratch/bad" && cp -r "$scratch/clean" "$scratch/bad"
    mkdir -p "$(dirname "$scratch/bad/$file")"
    printf '%s\n' "$text" >"$scratch/bad/$file"
    if check_tree "$scratch/bad" >/dev/null; then
      echo "check-includes self-test: NOT caught: $name ($file: $text)"; failed=1
    else
      echo "check-includes self-test: caught: $name"
    fi
  done
  return "$failed"
}

here=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = "--self-test" ]; then
  self_test "$here"
  echo "check-includes self-test: passed"
  exit 0
fi
root=${1:-$here}
check_tree "$root"
echo "check-includes: every module includes only the layers before it"
