#!/usr/bin/env bash
# Configures and builds the module, tools and tests into build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
"$(dirname "$0")/install-deps.sh"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -Wno-dev \
  -DCAUSTICS_WRAP_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3 > build.log 2>&1 ||
  { cat build.log >&2; echo "build.sh: CMake configuration failed (log above)" >&2; exit 1; }
cmake --build build --parallel "$(nproc)" >> build.log 2>&1 ||
  { tail -n 60 build.log >&2; echo "build.sh: build failed (see build.log)" >&2; exit 1; }
echo "build.sh: built into build/ (log: build.log)"
