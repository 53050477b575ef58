#!/usr/bin/env bash
# GUI smoke test: under a virtual X server, aggpack-gui packs a small lattice (--pack), saves a
# screenshot of its window (--screenshot) and exits (--quit); check_screenshot.py then inspects
# the picture. Usage: smoke_test.sh AGGPACK_GUI OUTPUT_DIR
set -euo pipefail
gui="$1"
out="$2"
cli="${3:-}"  # the aggpack CLI, for the Open check
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

# Open: a random packing made by the CLI is shown, and its stored configuration fills the panel
# (so Pack repeats or varies it), as the panel line of the scripted run reports.
if [ -n "$cli" ]; then
  rm -f "$out/random.h5" "$out/open.txt"
  "$cli" pack --progress none -o "$out/random.h5" --set packer.kind=random \
    --set container.length=0.3 --set container.width=0.25 --set container.depth=0.2 \
    --set particle.radius_min=0.03 --set particle.radius_max=0.05 \
    --set packer.target_fraction=0.15 --seed 7 > /dev/null
  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --open "$out/random.h5" --quit \
    --size 800x600 > "$out/open.txt" 2>&1 || { cat "$out/open.txt"; exit 1; }
  cat "$out/open.txt"
  grep -q "status: Opened .*random.h5: .* particles.* The panel shows its configuration." \
    "$out/open.txt"
  for expected in 'packer.kind="random"' 'packer.seed=7' 'container.length=0.3' \
    'container.width=0.25' 'container.depth=0.2' 'packer.target_fraction=0.15'; do
    grep "^panel:" "$out/open.txt" | grep -qF " $expected" ||
      { echo "panel line lacks $expected"; exit 1; }
  done
fi
