#!/usr/bin/env bash
# Renders the demo gallery: the sample tree, bush and conifer and the shared fern in the
# standard, expressive (Luft et al.), ink, pen, toon, watercolor and blobs (Dudley) styles, the
# shared needle and weeping trees in ink and pen (PNG, SVG, PDF), a contact sheet of
# every style per scene, their G-buffer previews, the normal buffers of Luft Fig. 7 (original,
# realigned, realigned-scaled), a rho/tau sweep (Luft Fig. 3), toon with cast shadows, toon
# and keyframed blob turntables (MP4), an ink turntable GIF, Hegeman AO on a ground plane and grass, a baked tree and the foliage trade-off plot. Usage: scripts/demo.sh SYLVA_BINARY OUT_DIR
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
  for style in expressive ink pen toon watercolor blobs; do
    "$sylva" render "$scene" --style "$style" --size 1024 --ssaa 2 --cache-dir "$out/cache" \
      -o "$out/$name-$style.png"
  done
  "$sylva" compare "$scene" --size 512 --ssaa 2 --cache-dir "$out/cache" -q \
    -o "$out/$name-sheet.png"
  "$sylva" buffers "$scene" --size 512 --out-dir "$out/$name-buffers" --id cluster
  for normals in original realigned realigned-scaled; do
    "$sylva" buffers "$scene" --size 512 --buffers normal --normals "$normals" \
      --cache-dir "$out/cache" --out-dir "$out/$name-normals-$normals"
  done
done
# Needle and weeping trees in ink and pen (issue "Ink for illustrators"), and the pen drawing
# as SVG and PDF (issue "Vector line art").
for tree in sapling_small_pine_s2 sapling_weeping_willow_s2; do
  for style in ink pen; do
    "$sylva" render "$shared/assets/$tree.glb" --style "$style" --size 1024 \
      --cache-dir "$out/cache" -o "$out/$tree-$style.png"
  done
  "$sylva" render "$shared/assets/$tree.glb" --style pen --size 1024 --cache-dir "$out/cache" \
    -o "$out/$tree-pen.svg"
  "$sylva" render "$shared/assets/$tree.glb" --style pen --size 1024 --dpi 300 \
    --cache-dir "$out/cache" -o "$out/$tree-pen.pdf"
done
"$sylva" compare "$out/tree.glb" --style expressive --sweep foliage.rho=3%,8%,20% \
  --sweep foliage.tau=auto,4,16 --size 384 --ssaa 2 --cache-dir "$out/cache" -q \
  -o "$out/tree-rho-tau-sheet.png"
"$sylva" compare "$out/tree.glb" --style toon --sweep toon.cast_shadows=false,true --size 768 \
  --ssaa 2 --cache-dir "$out/cache" -q -o "$out/tree-toon-shadows-sheet.png"
for kind in tree conifer; do
  "$sylva" turntable "$out/$kind.glb" --style toon --frames 72 --size 512 --ssaa 2 \
    --cache-dir "$out/cache" -q --report "$out/$kind-turntable-coherence.csv" \
    -o "$out/$kind-turntable-toon.mp4"
done
# A short looping GIF (one global palette) for web pages.
"$sylva" turntable "$out/tree.glb" --style ink --frames 36 --size 320 --ssaa 2 \
  --cache-dir "$out/cache" -q -o "$out/tree-turntable-ink.gif"
# Dudley's blobs: 16 clusters, keyframes every 8 frames (the coherence CSV has the jitter).
for kind in tree bush conifer; do
  "$sylva" render "$out/$kind.glb" --style blobs --clusters 16 --size 1024 --ssaa 2 \
    -o "$out/$kind-blobs-16.png"
  "$sylva" turntable "$out/$kind.glb" --style blobs --clusters 16 --frames 96 --size 512 \
    --keyframe-every 8 -q --report "$out/$kind-turntable-blobs-coherence.csv" \
    -o "$out/$kind-turntable-blobs.mp4"
done
# Hegeman et al.'s AO on a ground plane and a grass patch (Eq. 7-9): the AO buffers and renders.
"$sylva" buffers "$out/tree.glb" --ground --elevation 35 --size 768 --buffers ao \
  --set ao.model=hegeman-sphere --out-dir "$out/tree-ground-ao"
"$sylva" render "$out/tree.glb" --ground --elevation 35 --size 1024 --ssaa 2 --ambient 0.8 \
  --set ao.model=hegeman-sphere -o "$out/tree-ground-hegeman.png"
"$sylva" sample grass -o "$out/grass.glb"
"$sylva" buffers "$out/grass.glb" --elevation 30 --size 768 --buffers ao \
  --set ao.model=hegeman-sphere --out-dir "$out/grass-ao"
"$sylva" bake "$out/tree.glb" --cache-dir "$out/cache" -o "$out/tree-baked.glb"
"$sylva" render "$out/tree-baked.glb" --size 1024 --ssaa 2 -o "$out/tree-baked-standard.png"
"$sylva" tradeoff "$out/bush.glb" --study foliage --grids 32,64,128 -o "$out/bush-tradeoff.csv" \
  --plot "$out/bush-tradeoff.png"
echo
echo "demo: the gallery is in $out/:"
ls "$out"/*.png "$out"/*.mp4 | sed 's/^/  /'
echo "  and the buffer previews in $out/*-buffers/ and $out/*-normals-*/ (*.preview.png)"
