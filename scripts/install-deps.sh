#!/usr/bin/env bash
# Installs the Debian 12 packages the caustics module needs to build, render and
# test. Idempotent: packages already present are skipped by apt.
#
#   scripts/install-deps.sh          the build, the renders and the tests
#   scripts/install-deps.sh fuzz     also clang and libFuzzer (scripts/fuzz.sh)
#   scripts/install-deps.sh paraview also ParaView 5.11 (paraview-dev, which brings
#                                    paraview and pvbatch) for the ParaView plugin
#                                    (scripts/build-paraview-plugin.sh)
#
# Never python3-paraview: it Conflicts with python3-vtk9, on which libvtk9-dev (the
# main build's VTK 9.1) depends, so installing it would remove the main build's VTK.
# scripts/build-paraview-plugin.sh unpacks it into the build folder instead
# (docs/paraview.md). apt runs with --no-remove: it stops rather than remove a package.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libvtk9-dev mpi-default-dev libjsoncpp-dev   # VTK 9.1 (its CMake config finds MPI, jsoncpp)
  libglm-dev libopenimageio-dev libembree-dev   # maths, EXR/PNG, CPU reference ray queries
  libopenvdb-dev libnanovdb-dev                 # heterogeneous media
  libegl-dev libgl1-mesa-dri                    # headless EGL; Mesa llvmpipe
  xvfb xauth mesa-utils                         # an X server for tests
  libgtest-dev libbenchmark-dev                 # tests and micro-benchmarks
  python3-matplotlib python3-openimageio        # benchmark plots, EXR in scripts
  python3-dev python3-vtk9                      # Python wrapping (vtkcaustics)
)
case "${1:-}" in
  "") ;;
  fuzz) packages+=(clang libclang-rt-14-dev) ;; # libFuzzer with ASan and UBSan
  paraview) packages+=(paraview-dev) ;;         # ParaView 5.11 and its bundled VTK 9.2
  *) echo "install-deps: unknown group '$1' (known: fuzz, paraview)" >&2; exit 2 ;;
esac

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends --no-remove \
  "${missing[@]}"
