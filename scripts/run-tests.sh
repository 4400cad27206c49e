#!/usr/bin/env bash
# The second README command (and what CI runs): builds if needed, then runs the
# whole test suite under Xvfb (llvmpipe), two tests at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build
exec xvfb-run -a -s "-screen 0 1280x1024x24" ctest --output-on-failure --timeout 300 -j 2 "$@"
