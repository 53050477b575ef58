#!/usr/bin/env bash
# The GUI's Open refuses every bad native file of tests/io/fixtures/bad-inputs (README there) with
# the library's message naming the file and the field, exit 2 (a scripted run): the same
# read_packing as every CLI command (tests/io/native_bad_inputs_test.cpp) and aggpack.read
# (tests/python/test_bad_inputs.py). One X session for all files, for speed.
# Usage: bad_open_test.sh AGGPACK_GUI OUTPUT_DIR
set -euo pipefail
gui="$1"
out="$2"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
fixtures="$here/../io/fixtures/bad-inputs"
bad_files=()
for file in "$fixtures"/*.h5; do
  case "$(basename "$file")" in
    base_s.h5 | vlen_ascii.h5 | vlen_format_name.h5 | vlen_utf8_config_toml.h5 | \
      zero_particles.h5 | unparsable_config_toml.h5) ;;  # valid packings
    *) bad_files+=("$file") ;;
  esac
done
[ "${#bad_files[@]}" -eq 18 ] || { echo "expected 18 bad fixtures, found ${#bad_files[@]}"; exit 1; }
rm -f "$out/bad-open.txt"
xvfb-run -a -s "-screen 0 1280x800x24" bash -c '
  gui="$1"; out="$2"; shift 2
  for file in "$@"; do
    "$gui" --open "$file" --quit --size 640x480 > "$out/bad-one.txt" 2>&1
    echo "exit $? $(grep "^status: " "$out/bad-one.txt" | tail -n 1)" >> "$out/bad-open.txt"
  done' _ "$gui" "$out" "${bad_files[@]}" || true
cat "$out/bad-open.txt"
[ "$(wc -l < "$out/bad-open.txt")" -eq "${#bad_files[@]}" ] ||
  { echo "not every bad file was opened"; exit 1; }
for file in "${bad_files[@]}"; do
  grep -qF "exit 2 status: $file: /" "$out/bad-open.txt" ||
    { echo "the GUI did not refuse $file with its message and exit 2"; exit 1; }
done
