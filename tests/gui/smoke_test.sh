#!/usr/bin/env bash
# GUI smoke test: under a virtual X server, aggpack-gui packs a small lattice (--pack), saves a
# screenshot of its window (--screenshot) and exits (--quit); check_screenshot.py then inspects
# the picture. Usage: smoke_test.sh AGGPACK_GUI OUTPUT_DIR
set -euo pipefail
gui="$1"
out="$2"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$out"
rm -f "$out/screenshot.png" "$out/log.txt"
# 5 x 3 x 3 = 45 lattice sites: quick to pack even on a loaded machine.
xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --pack --quit --size 1200x760 \
  --screenshot "$out/screenshot.png" \
  --set container.length=1.0 --set container.width=0.6 --set container.depth=0.6 \
  > "$out/log.txt" 2>&1 || { cat "$out/log.txt"; exit 1; }
cat "$out/log.txt"
grep -q "status: Packing finished! 45 particles" "$out/log.txt"
python3 "$here/check_screenshot.py" "$out/screenshot.png" 1200 760
