#!/usr/bin/env bash
# CI check of the Debian package (as root, on a machine where aggpack is not installed): builds
# it (scripts/package.sh), installs it with apt, uses what it installed from a folder outside the
# tree (the CLI packs and exports the paper's case, the Python module packs from its
# dist-packages, man pages, desktop entry), then removes it and checks nothing is left.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${AGGPACK_BUILD_DIR:-build}
fail() {
  echo "package-test: $*" >&2
  exit 1
}
if dpkg -s aggpack >/dev/null 2>&1; then fail "aggpack is installed already: remove it first"; fi
scripts/package.sh
deb=$(ls "$build_dir"/aggpack_*_"$(dpkg --print-architecture)".deb)
version=$(dpkg-deb -f "$deb" Version)
depends=$(dpkg-deb -f "$deb" Depends)
echo "package-test: $deb, Depends: $depends"
# Depends come from the linked libraries (dpkg-shlibdeps) and the module's interpreter.
for needed in libhdf5 libtbb libglfw3 libbullet libfmt python3-numpy "python3 (<<"; do
  [[ $depends == *"$needed"* ]] || fail "Depends lacks $needed"
done

work=$(mktemp -d)
# On any failure after the install, the package is purged again: the machine is left as found.
cleanup() {
  rm -rf "$work"
  if dpkg -s aggpack >/dev/null 2>&1; then apt-get purge -y -q aggpack >/dev/null; fi
}
trap cleanup EXIT
apt-get install -y -q "./$deb"
cd "$work"
[ "$(command -v aggpack)" = /usr/bin/aggpack ] || fail "aggpack is not /usr/bin/aggpack"
[ "$(aggpack --version)" = "aggpack $version" ] || fail "aggpack --version: $(aggpack --version)"
aggpack pack -o paper.h5 >/dev/null
count=$(aggpack info paper.h5 | awk '/^particles/ {print $2}')
[ "$count" = 1050 ] || fail "the paper's case packed $count particles, not 1050"
aggpack export paper.h5 -o paper.stl --ascii >/dev/null
facets=$(grep -c "^  facet normal" paper.stl || true)
[ "$facets" -gt 1050 ] || fail "paper.stl has $facets facets"
env -u PYTHONPATH /usr/bin/python3 - <<'PY'
import aggpack
assert aggpack.__file__.startswith("/usr/lib/python3/dist-packages/"), aggpack.__file__
packing = aggpack.pack(aggpack.pack_config())
assert len(packing) == 1050, len(packing)
PY
for page in aggpack aggpack-pack aggpack-mesomodel; do
  man -w "$page" >/dev/null || fail "no man page $page"
done
man -P cat aggpack-pack 2>/dev/null | grep -q -- "--output" || fail "aggpack-pack(1) lacks --output"
desktop-file-validate /usr/share/applications/aggpack-gui.desktop
[ -f /usr/share/icons/hicolor/scalable/apps/aggpack.svg ] || fail "no icon"
[ -f /usr/share/doc/aggpack/examples/paper.toml ] || fail "no examples"
aggpack-gui --help >/dev/null || fail "aggpack-gui --help failed"
cd /

apt-get purge -y -q aggpack
if dpkg -s aggpack >/dev/null 2>&1; then fail "aggpack still installed after purge"; fi
for path in /usr/bin/aggpack /usr/bin/aggpack-gui /usr/share/doc/aggpack \
  /usr/lib/python3/dist-packages/aggpack* /usr/share/man/man1/aggpack.1.gz; do
  [ ! -e "$path" ] || fail "$path left after purge"
done
echo "package-test: $deb installed, used and removed cleanly"
