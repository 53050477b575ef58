#!/usr/bin/env bash
# The shape library dialog (particle.library) under a virtual X server:
#   1. opened on a folder of meshes, two files picked, answered "yes": the panel's field holds
#      exactly those files (name order), the dialog listed only the 3 mesh files (not the text
#      file), and the screenshot shows a drawn modal (check_ui.py dialog);
#   2. nothing picked, "yes": the field holds the folder; "no": the field stays unset;
#   3. a Pack with a library in the field places particles (the field reaches the packer);
#   4. Chinese: the same dialog in the catalogue's words (the same scripted line; a screenshot).
# Usage: library_test.sh AGGPACK_GUI OUTPUT_DIR
set -euo pipefail
export LANG=C.UTF-8
unset LC_ALL LC_MESSAGES
gui="$1"
out="$2"
here="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$out"
mkdir -p "$out/rocks/sub"
lib="$out/rocks"
# Meshes: a tetrahedron (STL), an octahedron (OBJ), a box (PLY, upper-case extension); a text
# file and a subfolder.
python3 - "$lib" <<'PY'
import sys
folder = sys.argv[1]
tetra = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
tris = [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]
with open(f"{folder}/a_tetra.stl", "w") as f:
    f.write("solid t\n")
    for t in tris:
        f.write("facet normal 0 0 0\nouter loop\n")
        for i in t:
            f.write("vertex {} {} {}\n".format(*tetra[i]))
        f.write("endloop\nendfacet\n")
    f.write("endsolid t\n")
octa = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
with open(f"{folder}/b_octa.obj", "w") as f:
    f.writelines("v {} {} {}\n".format(*v) for v in octa)
    f.writelines("f {} {} {}\n".format(*(i + 1 for i in t)) for t in faces)
box = [(x, y, z) for x in (0, 1) for y in (0, 2) for z in (0, 3)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
with open(f"{folder}/c_box.PLY", "w") as f:
    f.write("ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
            "property float z\nelement face 6\nproperty list uchar int vertex_indices\n"
            "end_header\n")
    f.writelines("{} {} {}\n".format(*v) for v in box)
    f.writelines("4 {} {} {} {}\n".format(*q) for q in quads)
with open(f"{folder}/notes.txt", "w") as f:
    f.write("not a mesh\n")
PY
run() {  # run NAME ARGS...: the GUI under Xvfb, its output in $out/NAME.txt
  local name="$1"
  shift
  xvfb-run -a -s "-screen 0 1280x800x24" "$gui" --settings-dir "$out/settings" --quit \
    --size 1200x760 "$@" > "$out/$name.txt" 2>&1 || { cat "$out/$name.txt"; exit 1; }
  cat "$out/$name.txt"
}
fail() { echo "FAIL: $*"; exit 1; }

# 1. Two files picked (in the other order: the field lists them in name order).
run picked --library-dialog "$lib" --library-pick c_box.PLY,b_octa.obj --answer yes \
  --screenshot "$out/library.png"
grep -qxF "dialog: library $lib (3 mesh files; picked: c_box.PLY b_octa.obj); answer yes" \
  "$out/picked.txt" || fail "the dialog did not list the 3 mesh files or take the picks"
grep -qF " particle.library=[\"$lib/b_octa.obj\",\"$lib/c_box.PLY\"]" "$out/picked.txt" ||
  fail "the panel's particle.library is not the two picked files"
python3 "$here/check_ui.py" library "$out/library.png" 1200 760

# 2. The whole folder; and "no" leaves the field unset.
run folder --library-dialog "$lib" --answer yes
grep -qF " particle.library=\"$lib\"" "$out/folder.txt" ||
  fail "the panel's particle.library is not the folder"
run refused --library-dialog "$lib" --library-pick a_tetra.stl --answer no
grep -q "^panel:" "$out/refused.txt" || fail "no panel line"
! grep -q "particle.library=" "$out/refused.txt" || fail "Cancel set particle.library"
grep -qxF "folder=$lib" "$out/settings/settings.ini" || fail "the library folder was not kept"

# 3. Pack with files in the field: particles placed.
small=(--set container.length=0.3 --set container.width=0.3 --set container.depth=0.3
  --set particle.radius=0.05)
run pack "${small[@]}" --set "particle.library=[\"$lib/a_tetra.stl\",\"$lib/b_octa.obj\"]" \
  --pack
grep -q "^status: Packing finished! [1-9][0-9]* particles" "$out/pack.txt" ||
  fail "a pack with the library did not finish"
grep -qF " particle.library=[\"$lib/a_tetra.stl\",\"$lib/b_octa.obj\"]" "$out/pack.txt" ||
  fail "the panel does not show the library given with --set"

# 4. Chinese.
LANG=zh_CN.UTF-8 run zh --library-dialog "$lib" --library-pick a_tetra.stl --answer yes \
  --screenshot "$out/library-zh.png"
grep -qxF "dialog: library $lib (3 mesh files; picked: a_tetra.stl); answer yes" "$out/zh.txt" ||
  fail "the Chinese run did not show the same dialog"
python3 "$here/check_ui.py" library "$out/library-zh.png" 1200 760
echo "library dialog: ok"
