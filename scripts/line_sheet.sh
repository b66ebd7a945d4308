#!/usr/bin/env bash
# The line styles' picture in docs/lines.md and the README: `standard`, `ink` and `pen` side by
# side on every shared tree (../shared/assets), one row per tree, small enough to commit.
# `make line-sheet` writes it to docs/line-sheet.png.
# Usage: scripts/line_sheet.sh SYLVA_BINARY OUT.png [SIZE]
set -euo pipefail
sylva=$1
out=$2
size=${3:-256}
shared=${SYLVA_SHARED_DIR:-"$(cd "$(dirname "$0")/.." && pwd)/../shared"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rows=()
for tree in eztree_ash_medium_s5 eztree_aspen_large_s9 polyhaven_fern_02 sapling_small_pine_s2 \
  sapling_weeping_willow_s2; do
  "$sylva" compare "$shared/assets/$tree.glb" --styles standard,ink,pen --size "$size" --ssaa 2 \
    --columns 3 --label-lines 0 -q -o "$tmp/$tree.png"
  rows+=(-i "$tmp/$tree.png")
done
ffmpeg -loglevel error -y "${rows[@]}" -filter_complex "vstack=inputs=5" -frames:v 1 \
  "$tmp/sheet.png"
mv "$tmp/sheet.png" "$out"
