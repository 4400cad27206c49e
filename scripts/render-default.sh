#!/usr/bin/env bash
# The first README command: installs dependencies, builds, and renders the default
# scene (the ball lens) with the best technique to caustics.png and caustics.exr.
# Extra arguments go to caustics-render (e.g. --size 1024, or another scene).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
# Headless machines render through EGL; exit code 3 means no OpenGL window could
# be made at all, and then Xvfb provides one.
status=0
build/bin/caustics-render --timings "$@" || status=$?
if [ "$status" -eq 3 ]; then
  echo "render-default.sh: no display or EGL; retrying under xvfb-run" >&2
  exec xvfb-run -a build/bin/caustics-render --timings "$@"
fi
exit "$status"
