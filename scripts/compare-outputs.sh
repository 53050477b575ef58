#!/usr/bin/env bash
# Refactoring check: runs two aggpack binaries on the same inputs and compares every output file
# byte for byte (cmp). Inputs: every examples/*.toml (pack configs: pack + every export; repose
# configs: the resolved config, a short repose run and a two-case sweep) and the paper's default
# case (`aggpack pack` with no config). Per packing it writes the native .h5, `info` (text and
# --json) and every export: STL binary + ASCII (+ one file per particle), OBJ, VTU surface +
# tetrahedra (fan and TetGen), rock.dat, Abaqus .inp C3D4 / C3D10 / parts, Gmsh .msh, LS-DYNA .k,
# ANSYS .mac, YADE .py, and the abaqus / calculix / lsdyna / yade decks; the default case also
# with --xdmf and --compression, a short settle and a short densify; the mesomodels of the
# mesomodel-cube (.inp, .msh, .vtu), mesomodel-cylinder and periodic-rve examples (.inp). Printed
# text is compared too, after masking timings ("0.14 s" -> "<T> s"); each command's exit code is
# compared.
#
#   scripts/compare-outputs.sh OLD_BINARY NEW_BINARY [OUTDIR]
#
# OUTDIR (default: a new /tmp/aggpack-compare.XXXXXX) gets old/ and new/ with the same relative
# names; both sides run at the same time (two processes). Prints one line per file (or output
# folder: per-particle STL, repose and sweep folders, compared file by file) and exits 1 on
# any difference (or a file only one side wrote), 0 when everything is identical. Each side's
# seconds per command go to OUTDIR/old.seconds and new.seconds (not compared).
# Environment: AGGPACK_COMPARE_SLOW=0 leaves out the sweeps and TetGen exports (faster).
set -uo pipefail

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
old_binary=$(realpath "$1")
new_binary=$(realpath "$2")
for binary in "$old_binary" "$new_binary"; do
  [ -x "$binary" ] || { echo "compare-outputs: $binary is not an executable" >&2; exit 2; }
done
repo=$(cd "$(dirname "$0")/.." && pwd)
out=${3:-$(mktemp -d /tmp/aggpack-compare.XXXXXX)}
mkdir -p "$out"
out=$(realpath "$out")
slow=${AGGPACK_COMPARE_SLOW:-1}

# ---- the commands: one per line, "NAME<tab>ARGUMENTS" (run inside old/ or new/) ----------------
commands() {
  local config name packings=()
  # The built-in default (the paper's case; examples/paper.toml holds the same keys).
  echo -e "default.pack\tpack -o default.h5 --progress none"
  echo -e "default.print-config\tpack --print-config"
  echo -e "default-xdmf.pack\tpack -o default-xdmf.h5 --xdmf --progress none"
  echo -e "default-deflate.pack\tpack -o default-deflate.h5 --compression 4 --progress none"
  packings+=(default)
  for config in "$repo"/examples/*.toml; do
    name=$(basename "$config" .toml)
    if grep -q '^\[trough\]' "$config"; then
      echo -e "$name.print-config\trepose $config --print-config"
      # Two layers of particles and 0.02 s per stage: the whole flow in seconds, not the result.
      local short="--set particle.fill_height=0.025 --set rest.max_time=0.02 --width 160"
      echo -e "$name.repose\trepose $config -o $name-repose $short --progress none"
      if [ "$slow" = 1 ]; then
        echo -e "$name.sweep\tsweep $config -o $name-sweep $short --set sweep.alphas=[0.5]" \
          "--set sweep.frictions=[0.2,0.4] --no-plot --progress none"
      fi
    else
      echo -e "$name.pack\tpack $config -o $name.h5 --progress none"
      echo -e "$name.print-config\tpack $config --print-config"
      packings+=("$name")
    fi
  done
  echo -e "repose-default.print-config\trepose --print-config"
  echo -e "sweep-default.print-config\tsweep --print-config"
  for name in "${packings[@]}"; do
    local in="$name.h5"
    echo -e "$name.info\tinfo $in"
    echo -e "$name.info-json\tinfo $in --json"
    echo -e "$name.stl\texport $in -o $name.stl"
    echo -e "$name.ascii-stl\texport $in -o $name.ascii.stl --ascii"
    echo -e "$name.per-particle\texport $in -o $name-per-particle --per-particle --format stl"
    echo -e "$name.obj\texport $in -o $name.obj"
    echo -e "$name.surface-vtu\texport $in -o $name.surface.vtu"
    echo -e "$name.tetra-vtu\texport $in -o $name.tetra.vtu --cells tetrahedra"
    echo -e "$name.dat\texport $in -o $name.dat"
    echo -e "$name.c3d4-inp\texport $in -o $name.c3d4.inp"
    echo -e "$name.c3d10-inp\texport $in -o $name.c3d10.inp --quadratic"
    echo -e "$name.parts-inp\texport $in -o $name.parts.inp --inp-layout parts"
    echo -e "$name.msh\texport $in -o $name.msh"
    echo -e "$name.surface-msh\texport $in -o $name.surface.msh --cells surface"
    echo -e "$name.k\texport $in -o $name.k"
    echo -e "$name.mac\texport $in -o $name.mac"
    echo -e "$name.py\texport $in -o $name.py"
    echo -e "$name.mm-stl\texport $in -o $name.mm.stl --scale 1000"
    echo -e "$name.abaqus-deck\texport $in --deck abaqus -o $name.abaqus-deck.inp"
    echo -e "$name.calculix-deck\texport $in --deck calculix -o $name.calculix-deck.inp"
    echo -e "$name.lsdyna-deck\texport $in --deck lsdyna -o $name.lsdyna-deck.k"
    echo -e "$name.yade-deck\texport $in --deck yade -o $name.yade-deck.py"
    if [ "$slow" = 1 ]; then
      echo -e "$name.tetgen-vtu\texport $in -o $name.tetgen.vtu --cells tetrahedra --tet-method tetgen"
    fi
  done
  # The mesomodels of the examples made for them: a box (the .inp with its face sets and a
  # compression step, .msh, .vtu), a cylinder (its circumscribed prism) and a periodic box (ties
  # and six load cases).
  for name in mesomodel-cube mesomodel-cylinder periodic-rve; do
    case " ${packings[*]} " in *" $name "*) ;; *) continue ;; esac
    echo -e "$name.meso-inp\tmesomodel $name.h5 -o $name.meso.inp --strain 0.001 --progress none"
  done
  if [[ " ${packings[*]} " == *" mesomodel-cube "* ]]; then
    echo -e "mesomodel-cube.meso-msh\tmesomodel mesomodel-cube.h5 -o mesomodel-cube.meso.msh --progress none"
    echo -e "mesomodel-cube.meso-vtu\tmesomodel mesomodel-cube.h5 -o mesomodel-cube.meso.vtu --progress none"
  fi
  echo -e "default.settle\tsettle default.h5 -o default-settled.h5 --max-time 0.02 --progress none"
  echo -e "default.densify\tdensify default.h5 -o default-dense.h5 --sweeps 3 --progress none"
  echo -e "default-xdmf.info\tinfo default-xdmf.h5"
}

# Timings vary from run to run; everything else printed must match.
mask() { sed -E -i 's/[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)? ?(s|ms|min)\b/<T> \3/g' "$1"; }

run_side() {  # run_side FOLDER BINARY: every command, in order, inside FOLDER
  local dir=$1 binary=$2 name arguments start
  rm -rf "$dir" "$dir.seconds" && mkdir -p "$dir"
  while IFS=$'\t' read -r name arguments; do
    start=$(date +%s.%N)
    # shellcheck disable=SC2086  # the arguments are words
    (cd "$dir" && "$binary" $arguments >"$name.stdout" 2>"$name.stderr")
    echo $? >"$dir/$name.exit"
    awk -v a="$start" -v b="$(date +%s.%N)" -v n="$name" 'BEGIN { printf "%s %.2f\n", n, b - a }' \
      >>"$dir.seconds"
    mask "$dir/$name.stdout"
    mask "$dir/$name.stderr"
  done < <(commands)
}

SECONDS=0
run_side "$out/old" "$old_binary" &
old_pid=$!
run_side "$out/new" "$new_binary" &
new_pid=$!
wait "$old_pid" "$new_pid"
run_seconds=$SECONDS

# ---- compare: one line per file; a per-particle folder is one line (diff -rq inside it) --------
bytes() {  # bytes PATH: a file's size, or the sum over a folder's files, or - when missing
  if [ -e "$1" ]; then find "$1" -type f -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }'; else echo -; fi
}
same=0
different=0
printf '%-10s %12s %12s  %s\n' result "old bytes" "new bytes" file
while IFS= read -r entry; do
  a="$out/old/$entry" b="$out/new/$entry"
  if [ ! -e "$a" ] || [ ! -e "$b" ]; then
    result="ONLY-$([ -e "$a" ] && echo OLD || echo NEW)"
  elif [ -d "$a" ]; then
    if diff -rq "$a" "$b" >/dev/null 2>&1; then result=same; else result=DIFFERENT; fi
  elif cmp -s "$a" "$b"; then
    result=same
  else
    result=DIFFERENT
  fi
  size_a=$(bytes "$a")
  size_b=$(bytes "$b")
  if [ "$result" = same ]; then same=$((same + 1)); else different=$((different + 1)); fi
  suffix=$({ [ -d "$a" ] || [ -d "$b" ]; } && echo /)
  printf '%-10s %12s %12s  %s\n' "$result" "$size_a" "$size_b" "$entry$suffix"
  if [ "$result" = DIFFERENT ] && [ -n "$suffix" ]; then
    diff -rq "$a" "$b" 2>&1 | sed "s@$out/@@g; s/^/             /" | head -10
  fi
done < <( (cd "$out/old" && find . -mindepth 1 -maxdepth 1; cd "$out/new" &&
  find . -mindepth 1 -maxdepth 1) | sed 's@^\./@@' | sort -u)

failed=$(cd "$out/new" && grep -L '^0$' ./*.exit | sed 's@^\./@@; s/\.exit$//' | tr '\n' ' ')
if [ -n "$failed" ]; then
  echo "compare-outputs: note: non-zero exit in new/ (see NAME.stderr): $failed"
fi
echo "compare-outputs: $same identical, $different different; ran in ${run_seconds} s;" \
  "outputs in $out"
if [ "$different" -ne 0 ]; then
  echo "compare-outputs: DIFFERENT (diff -r $out/old $out/new for text files)"
  exit 1
fi
echo "compare-outputs: identical"
