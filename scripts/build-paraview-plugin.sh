#!/usr/bin/env bash
# Builds the ParaView plugin (ParaView/, docs/paraview.md) into build-pv/ against
# Debian's ParaView 5.11 and runs its tests (ctest label `paraview`) under Xvfb.
# Not part of scripts/run-tests.sh or CI's default run. Arguments go to ctest.
#
#   scripts/build-paraview-plugin.sh            install, build, test
#   CAUSTICS_PARAVIEW_SKIP_TESTS=1 scripts/...  install and build only
#
# Debian's python3-paraview conflicts with python3-vtk9 (which the main build's
# libvtk9-dev needs), so it is never installed: its package is downloaded with apt
# and unpacked into build-pv/deps/python3-paraview, which the build (ParaView's
# CMake package refers to its files) and the tests (pvbatch's `paraview` Python
# package) use.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
scripts/install-deps.sh paraview

build=build-pv
mkdir -p "$build"
python_root="$PWD/$build/deps/python3-paraview"
ParaView/cmake/unpack-python3-paraview.sh "$python_root"

launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
cmake -S ParaView -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -Wno-dev "${launcher[@]}" \
  -DCAUSTICS_PARAVIEW_PYTHON_ROOT="$python_root" > "$build/configure.log" 2>&1 ||
  { cat "$build/configure.log" >&2; echo "build-paraview-plugin: configuration failed" >&2; exit 1; }
cmake --build "$build" --parallel "$(nproc)" > "$build/build.log" 2>&1 ||
  { tail -n 60 "$build/build.log" >&2; echo "build-paraview-plugin: build failed" >&2; exit 1; }
built=$(date +%s)
echo "build-paraview-plugin: built into $build/ in $(( built - start )) s" \
  "(plugin: $build/lib/paraview-plugins/Caustics/Caustics.so)"

if [ "${CAUSTICS_PARAVIEW_SKIP_TESTS:-0}" != 1 ]; then
  (cd "$build" && xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" \
    ctest --output-on-failure --timeout 300 -L paraview "$@")
  echo "build-paraview-plugin: tests passed in $(( $(date +%s) - built )) s"
fi
echo "build-paraview-plugin: done in $(( $(date +%s) - start )) s"
