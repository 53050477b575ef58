#!/usr/bin/env bash
# GUI smoke test: under a virtual X server, aggpack-gui packs a small lattice (--pack), saves a
# screenshot of its window (--screenshot) and exits (--quit); check_screenshot.py then inspects
# the picture. With the CLI it also opens CLI-made packings (a uniform and a sieve grading) and
# checks the panel they fill, and packs a sieve grading in the GUI. Then the dense packer kind:
# Pack, and the Cancel button (clicked with xdotool) stops its densifier.
# Usage: smoke_test.sh AGGPACK_GUI OUTPUT_DIR [AGGPACK_CLI]
set -euo pipefail
# The GUI in English (the checks read its English words; ui_test.sh runs it in Chinese too).
export LANG=C.UTF-8
unset LC_ALL LC_MESSAGES
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

# Sieve grading. The panel's sieve table must round-trip: a sieve-graded packing made by the CLI
# (the triaxial example, made smaller) fills the table when opened, and the panel line, given back
# to the CLI as --set keys, resolves to the configuration of the run that made the file (the one
# the file stores). Then the GUI packs a sieve configuration itself.
if [ -n "$cli" ]; then
  example="$here/../../examples/triaxial-cylinder.toml"
  small=(--set container.height=0.04 --set packer.target_fraction=0.15)
  rm -f "$out/sieve.h5" "$out/sieve-open.txt" "$out/sieve-pack.txt" "$out/sieve.png"
  "$cli" pack --progress none "$example" "${small[@]}" -o "$out/sieve.h5" > /dev/null
  xvfb-run -a -s "-screen 0 1400x900x24" "$gui" --open "$out/sieve.h5" --quit --size 1300x850 \
    --screenshot "$out/sieve.png" > "$out/sieve-open.txt" 2>&1 ||
    { cat "$out/sieve-open.txt"; exit 1; }
  cat "$out/sieve-open.txt"
  python3 "$here/check_screenshot.py" "$out/sieve.png" 1300 850
  grep -q "status: Opened .*sieve.h5: .* particles.* The panel shows its configuration." \
    "$out/sieve-open.txt"
  panel="$(grep "^panel:" "$out/sieve-open.txt")"
  for expected in 'packer.kind="random"' 'container.kind="cylinder"' 'grading.kind="sieve"' \
    'grading.sieve=[[0.005,0.0],[0.008,20.0],[0.0112,50.0],[0.016,100.0]]'; do
    grep -qF " $expected" <<< "$panel" || { echo "panel line lacks $expected"; exit 1; }
  done
  read -ra entries <<< "${panel#panel:}"
  panel_args=()
  for entry in "${entries[@]}"; do panel_args+=(--set "$entry"); done
  diff <("$cli" pack --print-config "$example" "${small[@]}") \
    <("$cli" pack --print-config "${panel_args[@]}") ||
    { echo "the panel's configuration differs from the stored one"; exit 1; }

  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" "$example" "${small[@]}" --pack --quit \
    --size 800x600 > "$out/sieve-pack.txt" 2>&1 || { cat "$out/sieve-pack.txt"; exit 1; }
  cat "$out/sieve-pack.txt"
  grep -q "status: Packing finished! [0-9]* particles" "$out/sieve-pack.txt"
  grep "^panel:" "$out/sieve-pack.txt" |
    grep -qF ' grading.sieve=[[0.005,0.0],[0.008,20.0],[0.0112,50.0],[0.016,100.0]]' ||
    { echo "the packing panel line lacks the sieve table"; exit 1; }
fi

# Concrete mesomodel export (issue 16), the Mesomodel buttons' path run by script: open a packing,
# mesh it on the background job and write NAME-mesomodel.inp; an ITZ too thick for the packing's
# gaps is refused with the mesher's message, exit 2 and no file. Then the cohesive ITZ model and
# a solver deck (issue 18, item 5).
if [ -n "$cli" ]; then
  rm -f "$out/meso.h5" "$out/meso-mesomodel.inp" "$out/meso.txt" "$out/meso-bad.txt"
  "$cli" pack --progress none -o "$out/meso.h5" --set packer.kind=random \
    --set container.length=0.3 --set container.width=0.25 --set container.depth=0.2 \
    --set particle.radius_min=0.03 --set particle.radius_max=0.05 \
    --set packer.target_fraction=0.15 --set packer.gap=0.004 --seed 7 > /dev/null
  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --open "$out/meso.h5" --quit --size 800x600 \
    --export-name "$out/meso" --mesomodel-export inp --mesomodel-itz 0.5 > "$out/meso.txt" 2>&1 ||
    { cat "$out/meso.txt"; exit 1; }
  cat "$out/meso.txt"
  grep -q "status: Wrote .*meso-mesomodel.inp: mesomodel of [0-9]* aggregates, ITZ 0.5 mm" \
    "$out/meso.txt"
  grep -q "^\*ELSET, ELSET=ITZ" "$out/meso-mesomodel.inp" ||
    { echo "the mesomodel .inp has no ITZ element set"; exit 1; }
  rm -f "$out/meso-mesomodel.inp"
  # The GUI's own exit status, recorded inside the X session: xvfb-run's status can be its own
  # (5 when it fails to clean up its temporary folder while other tests use X too).
  rm -f "$out/meso-bad.status"
  xvfb-run -a -s "-screen 0 1280x800x24" bash -c '
    "$1" --open "$2.h5" --quit --size 800x600 --export-name "$2" --mesomodel-export inp \
      --mesomodel-itz 50 > "$2-bad.txt" 2>&1
    echo $? > "$2-bad.status"' _ "$gui" "$out/meso" || true
  cat "$out/meso-bad.txt"
  status=$(cat "$out/meso-bad.status" 2> /dev/null || echo none)
  [ "$status" = 2 ] || { echo "a refused mesomodel export exited $status, not 2"; exit 1; }
  grep -q "status: particles .* ITZ layers .* is not allowed" "$out/meso-bad.txt"
  [ ! -e "$out/meso-mesomodel.inp" ] || { echo "a refused export left a file"; exit 1; }

  # The cohesive ITZ model (the combo "ITZ model: cohesive elements"): the .inp joins aggregates
  # and mortar by COH3D6 wedges, as many as the status line says; with an ITZ thickness of 0 the
  # field says why in plain words, the export is refused (exit 2) and nothing is written.
  rm -f "$out/cohesive-mesomodel.inp" "$out/cohesive.txt" "$out/cohesive-zero.txt"
  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --settings-dir "$out/settings" --open \
    "$out/meso.h5" --quit --size 800x600 --export-name "$out/cohesive" --mesomodel-export inp \
    --mesomodel-itz 0.5 --mesomodel-itz-kind cohesive > "$out/cohesive.txt" 2>&1 ||
    { cat "$out/cohesive.txt"; exit 1; }
  cat "$out/cohesive.txt"
  cohesive=$(sed -n 's/^status: Wrote .*cohesive-mesomodel.inp: mesomodel of [0-9]* aggregates, ITZ 0.5 mm (cohesive), .* and \([0-9]*\) cohesive elements (COH3D6).*/\1/p' \
    "$out/cohesive.txt")
  [ -n "$cohesive" ] && [ "$cohesive" -gt 0 ] ||
    { echo "no cohesive element count in the status line"; exit 1; }
  grep -q "TYPE=COH3D6" "$out/cohesive-mesomodel.inp" ||
    { echo "the cohesive mesomodel .inp has no COH3D6 elements"; exit 1; }
  wedges=$(awk '/^\*ELEMENT, TYPE=COH3D6/ { on = 1; next } /^\*/ { on = 0 } on && NF { n++ }
    END { print n + 0 }' "$out/cohesive-mesomodel.inp")
  [ "$wedges" = "$cohesive" ] ||
    { echo "the .inp holds $wedges COH3D6 elements, the status says $cohesive"; exit 1; }
  rm -f "$out/cohesive-zero.status"
  xvfb-run -a -s "-screen 0 1280x800x24" bash -c '
    "$1" --settings-dir "$2/settings" --open "$2/meso.h5" --quit --size 800x600 \
      --export-name "$2/cohesive-zero" --mesomodel-export inp --mesomodel-itz 0 \
      --mesomodel-itz-kind cohesive > "$2/cohesive-zero.txt" 2>&1
    echo $? > "$2/cohesive-zero.status"' _ "$gui" "$out" || true
  cat "$out/cohesive-zero.txt"
  status=$(cat "$out/cohesive-zero.status" 2> /dev/null || echo none)
  [ "$status" = 2 ] || { echo "a cohesive ITZ of 0 mm exited $status, not 2"; exit 1; }
  grep -q "^field error: ITZ thickness (mm): Cohesive elements need an ITZ thickness above 0" \
    "$out/cohesive-zero.txt"
  [ ! -e "$out/cohesive-zero-mesomodel.inp" ] || { echo "a refused export left a file"; exit 1; }

  # A complete solver deck (File > Export solver deck > CalculiX, `aggpack export --deck
  # calculix`), through the Export dialog on the background job: the deck has its steps and
  # nodes; its node count is the packing's (the centroid fan: each particle's vertices, counted
  # in the CLI's OBJ of the same file, plus its centroid) and the status line's; and it is the
  # very file the CLI writes.
  rm -rf "$out/deck" "$out/deck.txt"
  mkdir -p "$out/deck"
  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --settings-dir "$out/settings" --open \
    "$out/meso.h5" --quit --size 1000x700 --export-deck calculix --export-name "$out/deck/rock" \
    --answer yes > "$out/deck.txt" 2>&1 || { cat "$out/deck.txt"; exit 1; }
  cat "$out/deck.txt"
  grep -q "^dialog: export CalculiX deck (.inp) to .*/deck/rock-calculix.inp" "$out/deck.txt"
  read -r particles nodes < <(sed -n 's/^status: Wrote .*rock-calculix.inp: CalculiX deck (.inp), \([0-9]*\) particles, \([0-9]*\) nodes.*/\1 \2/p' \
    "$out/deck.txt")
  [ -n "${nodes:-}" ] || { echo "no deck line in the status"; exit 1; }
  deck="$out/deck/rock-calculix.inp"
  for keyword in '^\*STEP' '^\*NODE, NSET=ALLNODES' '^\*ELEMENT, TYPE=C3D4' '^\*CONTACT PAIR'; do
    grep -q "$keyword" "$deck" || { echo "the deck lacks $keyword"; exit 1; }
  done
  [ "$(grep -c '^\*STEP' "$deck")" = 3 ] || { echo "the deck has not its 3 steps"; exit 1; }
  written=$(awk '/^\*NODE, NSET=ALLNODES/ { on = 1; next } /^\*/ { on = 0 } on && NF { n++ }
    END { print n + 0 }' "$deck")
  "$cli" export "$out/meso.h5" -o "$out/deck/surface.obj" > /dev/null
  vertices=$(grep -c '^v ' "$out/deck/surface.obj")
  [ "$written" = "$nodes" ] && [ "$written" = $((vertices + particles)) ] ||
    { echo "deck nodes $written, status $nodes, packing $vertices + $particles"; exit 1; }
  "$cli" export "$out/meso.h5" --deck calculix -o "$out/deck/cli.inp" > /dev/null
  cmp "$deck" "$out/deck/cli.inp" || { echo "the GUI's deck differs from the CLI's"; exit 1; }
fi

# The dense kind (examples/dense-box.toml, a budget it cannot finish for minutes): Pack at start,
# click Cancel (the job section is at the top of the panel: Pack at x 8-128, Cancel right of it,
# y ~37 below the title bar); the run ends cancelled with the last verified state shown. The click
# comes after 5 s, in the densify phase on an idle machine but possibly still in the fill on a
# loaded one, so the count of particles is not pinned (both phases keep a verified state).
command -v xdotool > /dev/null || { echo "xdotool is missing (scripts/install-deps.sh)"; exit 1; }
rm -f "$out/dense-cancel.txt" "$out/dense-cancel.png"
xvfb-run -a -s "-screen 0 1000x700x24" bash -c '
  "$1" "$2" --set densify.max_sweeps=1000000 --pack --quit --size 1000x700 \
    --screenshot "$3.png" > "$3.txt" 2>&1 &
  pid=$!
  sleep 5
  xdotool mousemove 236 37 click 1
  wait $pid' _ "$gui" "$here/../../examples/dense-box.toml" "$out/dense-cancel" ||
  { cat "$out/dense-cancel.txt"; exit 1; }
cat "$out/dense-cancel.txt"
grep -Eq "status: Cancelled: [0-9]+ particles" "$out/dense-cancel.txt"
grep -q "^Warning: cancelled; the packing holds the last verified state" "$out/dense-cancel.txt"
python3 "$here/check_screenshot.py" "$out/dense-cancel.png" 1000 700
