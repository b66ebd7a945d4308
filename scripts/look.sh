#!/bin/bash
# scripts/look.sh OUT [edges|ink|toon|watercolor]...: builds tests/look/look_images and writes
# the look images of single passes on synthetic scenes into OUT (all four sets by default), for
# judging a pass by eye after a change. Not a test: nothing checks what they look like.
# BUILD names the build folder (default build, configured by `make build`).
set -euo pipefail
if [ $# -lt 1 ]; then
  echo "usage: scripts/look.sh OUT [edges|ink|toon|watercolor]..." >&2
  exit 2
fi
build=${BUILD:-build}
cmake --build "$build" --target look_images >/dev/null
exec "$build/tests/look/look_images" "$@"
