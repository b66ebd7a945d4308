#!/usr/bin/env bash
# The pictures in the README and docs/lines.md: styles side by side on every shared tree
# (../shared/assets), one row per tree, small enough to commit. `make line-sheet` writes
# `standard`, `ink` and `pen` to docs/line-sheet.png; `make wash-sheet` writes `standard`,
# `watercolor`, `pen-and-wash` and `toon-ink` to docs/wash-sheet.jpg.
# Usage: scripts/tree_sheet.sh SYLVA_BINARY OUT.png|OUT.jpg [SIZE [STYLES]]   (STYLES comma-separated)
set -euo pipefail
sylva=$1
out=$2
size=${3:-256}
styles=${4:-standard,ink,pen}
columns=$(($(tr -cd ',' <<<"$styles" | wc -c) + 1))
shared=${SYLVA_SHARED_DIR:-"$(cd "$(dirname "$0")/.." && pwd)/../shared"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rows=()
for tree in eztree_ash_medium_s5 eztree_aspen_large_s9 polyhaven_fern_02 sapling_small_pine_s2 \
  sapling_weeping_willow_s2; do
  "$sylva" compare "$shared/assets/$tree.glb" --styles "$styles" --size "$size" --ssaa 2 \
    --columns "$columns" --label-lines 0 -q -o "$tmp/$tree.png"
  rows+=(-i "$tmp/$tree.png")
done
# A painted sheet is kept as JPEG (the paper's grain does not compress losslessly).
ext=${out##*.}
quality=()
[[ $ext == jpg ]] && quality=(-q:v 3)
ffmpeg -loglevel error -y "${rows[@]}" -filter_complex "vstack=inputs=5" -frames:v 1 \
  "${quality[@]}" "$tmp/sheet.$ext"
mv "$tmp/sheet.$ext" "$out"
