#!/usr/bin/env bash
# Builds the Debian package build/aggpack_<version>_<arch>.deb from the normal build (scripts/
# build.sh's folder and flags, so after the quick start it compiles nothing; only the install
# prefix becomes /usr): aggpack, aggpack-gui (desktop entry, icon), the Python module, man pages,
# docs and examples. Install it with `sudo apt install ./build/aggpack_*.deb`.
# Needs dpkg-dev (dpkg-shlibdeps works out Depends) and help2man (scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${AGGPACK_BUILD_DIR:-build}
for tool in dpkg-shlibdeps help2man; do
  command -v "$tool" >/dev/null || {
    echo "package.sh: $tool is missing (apt-get install dpkg-dev help2man)" >&2
    exit 1
  }
done
scripts/build.sh -DCMAKE_INSTALL_PREFIX=/usr
(cd "$build_dir" && cpack -G DEB)
ls "$build_dir"/aggpack_*.deb
