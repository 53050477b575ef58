#!/usr/bin/env bash
# Fails when a source file in src/, app/ or python/ is longer than the limit (600 lines, the
# project's "a file you can read in one sitting" rule: docs/architecture.md, "Checks"). Counts
# every line (wc -l) of the C++ and Python files git would see there (*.cpp, *.cc, *.h, *.hpp,
# *.py), so a long file must be split by concept, not squeezed.
#
#   scripts/check-file-sizes.sh [ROOT]     check the tree at ROOT (default: this checkout)
#   scripts/check-file-sizes.sh --self-test
#       makes a small tree of short files (and a long non-source file) in a temporary folder,
#       checks that it passes, then plants one long file of each kind (a .cpp in src/, a header
#       in app/, a .py in python/, one in a nested folder) and checks that each one fails, and
#       that a file of exactly the limit passes.
# Environment: AGGPACK_MAX_FILE_LINES (default 600).
set -euo pipefail

max_lines=${AGGPACK_MAX_FILE_LINES:-600}
folders=(src app python)

check_tree() {  # check_tree ROOT -> prints one line per file over the limit; returns 1 if any
  local root=$1 folder failures=0 lines file
  for folder in "${folders[@]}"; do
    [ -d "$root/$folder" ] || continue
    while IFS= read -r -d '' file; do
      lines=$(wc -l <"$file")
      if [ "$lines" -gt "$max_lines" ]; then
        echo "check-file-sizes: ${file#"$root"/} has $lines lines (at most $max_lines: split it by concept)"
        failures=1
      fi
    done < <(find "$root/$folder" -type f \( -name '*.cpp' -o -name '*.cc' -o -name '*.h' \
      -o -name '*.hpp' -o -name '*.py' \) -print0 | sort -z)
  done
  return "$failures"
}

self_test() {  # a small tree of its own, so the test does not depend on today's files
  local scratch
  scratch=$(mktemp -d)
  trap 'rm -rf "$scratch"' RETURN
  mkdir -p "$scratch/clean/src/core" "$scratch/clean/src/io" "$scratch/clean/app/gui" \
    "$scratch/clean/python"
  seq 20 | sed 's/^/\/\/ line /' >"$scratch/clean/src/core/short.cpp"
  seq 300 | sed 's/^/\/\/ line /' >"$scratch/clean/app/gui/short.h"
  seq 40 | sed 's/^/# line /' >"$scratch/clean/python/short.py"
  # A long file that is not source (data, docs) does not count.
  seq $((max_lines * 2)) >"$scratch/clean/src/io/table.txt"
  if ! check_tree "$scratch/clean" >/dev/null; then
    echo "check-file-sizes self-test: the clean tree already fails"
    return 1
  fi
  local -a cases=(
    "long source file|src/core/self_test_long.cpp|$((max_lines + 1))"
    "long header in app/|app/gui/self_test_long.h|$((max_lines + 40))"
    "long Python file|python/self_test_long.py|$((max_lines + 1))"
    "long file in a nested folder|src/io/nested/self_test_long.cc|$((max_lines * 2))"
  )
  local entry name file count failed=0
  for entry in "${cases[@]}"; do
    IFS='|' read -r name file count <<<"$entry"
    rm -rf "$scratch/bad" && cp -r "$scratch/clean" "$scratch/bad"
    mkdir -p "$(dirname "$scratch/bad/$file")"
    seq "$count" | sed 's/^/\/\/ line /' >"$scratch/bad/$file"
    if check_tree "$scratch/bad" >/dev/null; then
      echo "check-file-sizes self-test: NOT caught: $name ($file, $count lines)"; failed=1
    else
      echo "check-file-sizes self-test: caught: $name"
    fi
  done
  # A file of exactly the limit is allowed.
  rm -rf "$scratch/bad" && cp -r "$scratch/clean" "$scratch/bad"
  seq "$max_lines" | sed 's/^/\/\/ line /' >"$scratch/bad/src/core/self_test_at_limit.cpp"
  if check_tree "$scratch/bad" >/dev/null; then
    echo "check-file-sizes self-test: passed: a file of exactly $max_lines lines"
  else
    echo "check-file-sizes self-test: WRONGLY failed: a file of exactly $max_lines lines"; failed=1
  fi
  return "$failed"
}

here=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = "--self-test" ]; then
  self_test
  echo "check-file-sizes self-test: passed"
  exit 0
fi
root=${1:-$here}
check_tree "$root"
echo "check-file-sizes: no file in ${folders[*]} is over $max_lines lines"
