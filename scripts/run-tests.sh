#!/usr/bin/env bash
# The second README command (and what CI runs): builds if needed, then runs the
# whole test suite under Xvfb (llvmpipe), two tests at a time, then the tests that
# need no GPU stage again on an AddressSanitizer + UndefinedBehaviorSanitizer build
# (scripts/sanitize.sh; CAUSTICS_SKIP_SANITIZERS=1 skips that part), then a short
# libFuzzer run of each fuzz target (scripts/fuzz.sh smoke; CAUSTICS_SKIP_FUZZ=1
# skips it). Arguments go to the first ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
(cd build && xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure --timeout 300 -j 2 "$@")
if [ "${CAUSTICS_SKIP_SANITIZERS:-0}" != 1 ]; then
  scripts/sanitize.sh
fi
# Each libFuzzer target for a few thousand inputs (clang; CAUSTICS_SKIP_FUZZ=1 skips).
if [ "${CAUSTICS_SKIP_FUZZ:-0}" != 1 ]; then
  scripts/install-deps.sh fuzz
  scripts/fuzz.sh smoke
fi
