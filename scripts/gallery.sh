#!/usr/bin/env bash
# The README's picture: a contact sheet of every built-in style on the shared ash (a real tree,
# ../shared/assets/eztree_ash_medium_s5.glb), small enough to commit. `make gallery` writes it to
# docs/gallery.png; the demo writes the same sheet into its output folder first.
# Usage: scripts/gallery.sh SYLVA_BINARY OUT.png [CACHE_DIR]
set -euo pipefail
sylva=$1
out=$2
shared=${SYLVA_SHARED_DIR:-"$(cd "$(dirname "$0")/.." && pwd)/../shared"}
cache=()
if [ $# -ge 3 ]; then cache=(--cache-dir "$3"); fi
"$sylva" compare "$shared/assets/eztree_ash_medium_s5.glb" --size 256 --ssaa 2 --columns 4 \
  --label-lines 0 "${cache[@]}" -q -o "$out"
