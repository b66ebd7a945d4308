#!/usr/bin/env bash
# Renders the demo gallery: the sample tree, bush and conifer and the shared fern in the
# standard style, plus their G-buffer previews. Usage: scripts/demo.sh SYLVA_BINARY OUT_DIR
set -euo pipefail
sylva=$1
out=$2
shared=${SYLVA_SHARED_DIR:-"$(cd "$(dirname "$0")/.." && pwd)/../shared"}
mkdir -p "$out"
for kind in tree bush conifer; do
  "$sylva" sample "$kind" --seed 1 -o "$out/$kind.glb"
done
scenes=("$out/tree.glb" "$out/bush.glb" "$out/conifer.glb" "$shared/assets/polyhaven_fern_02.glb")
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .glb)
  "$sylva" render "$scene" --style standard --size 1024 --ssaa 2 -o "$out/$name-standard.png"
  "$sylva" buffers "$scene" --size 512 --out-dir "$out/$name-buffers" --id cluster
done
echo
echo "demo: the gallery is in $out/:"
ls "$out"/*.png | sed 's/^/  /'
echo "  and the buffer previews in $out/*-buffers/*.preview.png"
