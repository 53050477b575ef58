#!/usr/bin/env bash
# Installs every Debian bookworm package aggpack needs to build, test and run (as root).
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
packages=(
  # build
  build-essential cmake ninja-build pkg-config git
  # compiler cache shared by every build folder and clone (cmake/ccache.cmake)
  ccache
  # the Debian package (scripts/package.sh): Depends from the linked libraries, man pages
  dpkg-dev help2man desktop-file-utils
  # core + io libraries
  libeigen3-dev libtbb-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libfmt-dev
  libhdf5-dev
  # meshing, physics, rendering, GUI
  libtet1.5-dev libbullet-dev libosmesa6-dev libegl-dev libgl-dev libglfw3-dev libimgui-dev
  libstb-dev
  # convex hulls of imported particle shapes (particle.library)
  libqhull-dev
  # aggpack-gui in Chinese: a CJK font found at run time (Noto Sans CJK SC; ~50 MB installed)
  fonts-noto-cjk
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev clang-format
  # naming and bugprone checks (scripts/tidy.sh, .clang-tidy)
  clang-tidy
  # fuzzing (scripts/fuzz.sh): clang with libFuzzer and the sanitizer runtimes
  clang-14 libclang-rt-14-dev
  # independent readers used by the tests, and tools used by commands
  admesh calculix-ccx gmsh python3 python3-meshio python3-vtk9 python3-h5py python3-numpy
  xvfb xauth xdotool gnuplot-nox
  # statistics of the long benchmark scripts (bench/run_shape_effect.sh: t quantiles, Welch test)
  python3-scipy
  # the Python module (python/, pybind11) and its tests and examples
  pybind11-dev python3-dev python3-pytest python3-matplotlib
  # the manual's commands run by a test (tests/docs): its markdown parser
  python3-markdown-it
  # `mpirun -n N aggpack sweep` (optional, cmake/mpi.cmake)
  libopenmpi-dev openmpi-bin
  # runs the exported YADE deck (export --deck yade); ~105 MB download, ~1.1 GB installed
  yade
)
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${packages[@]}"
