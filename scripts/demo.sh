#!/usr/bin/env bash
# Renders the demo gallery into OUT_DIR, one progress line per picture ("[3/58] out/tree-ink.png
# 2.1 s, 0:14 in"), the commands' own messages going to OUT_DIR/demo.log. First the sample tree
# in the standard style and the README's sheet of every style on the shared ash
# (scripts/gallery.sh); then the sample tree, bush and conifer and the shared fern in the
# standard, expressive (Luft et al.), ink, pen, toon, watercolor and blobs (Dudley) styles, the
# shared needle and weeping trees in ink and pen (PNG, SVG, PDF), a contact sheet of every style
# per scene, their G-buffer previews, the normal buffers of Luft Fig. 7 (original, realigned,
# realigned-scaled), a rho/tau sweep (Luft Fig. 3), toon with cast shadows, toon and keyframed
# blob turntables (MP4), an ink turntable GIF, Hegeman AO on a ground plane and grass, a baked
# tree and the foliage trade-off plot.
# Usage: scripts/demo.sh SYLVA_BINARY OUT_DIR
set -euo pipefail
sylva=$1
out=$2
here=$(cd "$(dirname "$0")" && pwd)
shared=${SYLVA_SHARED_DIR:-"$here/../../shared"}
export SYLVA_SHARED_DIR=$shared
mkdir -p "$out"
log="$out/demo.log"
: >"$log"
cache="$out/cache"
counting=1 # the first pass over gallery() only counts the pictures
total=0
made=0
start=$SECONDS

# run CMD...: runs a step, its output into the log; on failure says which and shows the log's end.
run() {
  [ $counting = 0 ] || return 0
  if ! "$@" >>"$log" 2>&1; then
    echo "demo: failed: $*" >&2
    tail -n 5 "$log" >&2
    exit 1
  fi
}

# pic WHAT CMD...: run, then a progress line naming WHAT (the picture, or the folder of them).
pic() {
  local what=$1
  shift
  if [ $counting = 1 ]; then
    total=$((total + 1))
    return 0
  fi
  local t0=$SECONDS
  run "$@"
  made=$((made + 1))
  local in=$((SECONDS - start))
  printf '[%d/%d] %s  %d s, %d:%02d in\n' "$made" "$total" "$what" $((SECONDS - t0)) \
    $((in / 60)) $((in % 60))
}

gallery() {
  for kind in tree bush conifer; do
    run "$sylva" sample "$kind" --seed 1 -o "$out/$kind.glb"
  done
  pic "$out/tree-standard.png" "$sylva" render "$out/tree.glb" --style standard --size 1024 \
    --ssaa 2 -o "$out/tree-standard.png"
  pic "$out/gallery.png" "$here/gallery.sh" "$sylva" "$out/gallery.png" "$cache"
  scenes=("$out/tree.glb" "$out/bush.glb" "$out/conifer.glb" "$shared/assets/polyhaven_fern_02.glb")
  for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .glb)
    [ "$name" = tree ] || pic "$out/$name-standard.png" "$sylva" render "$scene" \
      --style standard --size 1024 --ssaa 2 -o "$out/$name-standard.png"
    for style in expressive ink pen toon watercolor blobs; do
      pic "$out/$name-$style.png" "$sylva" render "$scene" --style "$style" --size 1024 --ssaa 2 \
        --cache-dir "$cache" -o "$out/$name-$style.png"
    done
    pic "$out/$name-sheet.png" "$sylva" compare "$scene" --size 512 --ssaa 2 --cache-dir "$cache" \
      -q -o "$out/$name-sheet.png"
    pic "$out/$name-buffers/" "$sylva" buffers "$scene" --size 512 --out-dir "$out/$name-buffers" \
      --id cluster
    for normals in original realigned realigned-scaled; do
      pic "$out/$name-normals-$normals/" "$sylva" buffers "$scene" --size 512 --buffers normal \
        --normals "$normals" --cache-dir "$cache" --out-dir "$out/$name-normals-$normals"
    done
  done
  # Needle and weeping trees in ink and pen, and the pen drawing as SVG and PDF.
  for tree in sapling_small_pine_s2 sapling_weeping_willow_s2; do
    for style in ink pen; do
      pic "$out/$tree-$style.png" "$sylva" render "$shared/assets/$tree.glb" --style "$style" \
        --size 1024 --cache-dir "$cache" -o "$out/$tree-$style.png"
    done
    pic "$out/$tree-pen.svg" "$sylva" render "$shared/assets/$tree.glb" --style pen --size 1024 \
      --cache-dir "$cache" -o "$out/$tree-pen.svg"
    pic "$out/$tree-pen.pdf" "$sylva" render "$shared/assets/$tree.glb" --style pen --size 1024 \
      --dpi 300 --cache-dir "$cache" -o "$out/$tree-pen.pdf"
  done
  pic "$out/tree-rho-tau-sheet.png" "$sylva" compare "$out/tree.glb" --style expressive \
    --sweep foliage.rho=3%,8%,20% --sweep foliage.tau=auto,4,16 --size 384 --ssaa 2 \
    --cache-dir "$cache" -q -o "$out/tree-rho-tau-sheet.png"
  pic "$out/tree-toon-shadows-sheet.png" "$sylva" compare "$out/tree.glb" --style toon \
    --sweep toon.cast_shadows=false,true --size 768 --ssaa 2 --cache-dir "$cache" -q \
    -o "$out/tree-toon-shadows-sheet.png"
  for kind in tree conifer; do
    pic "$out/$kind-turntable-toon.mp4" "$sylva" turntable "$out/$kind.glb" --style toon \
      --frames 72 --size 512 --ssaa 2 --cache-dir "$cache" -q \
      --report "$out/$kind-turntable-coherence.csv" -o "$out/$kind-turntable-toon.mp4"
  done
  # A short looping GIF (one global palette) for web pages.
  pic "$out/tree-turntable-ink.gif" "$sylva" turntable "$out/tree.glb" --style ink --frames 36 \
    --size 320 --ssaa 2 --cache-dir "$cache" -q -o "$out/tree-turntable-ink.gif"
  # Dudley's blobs: 16 clusters, keyframes every 8 frames (the coherence CSV has the jitter).
  for kind in tree bush conifer; do
    pic "$out/$kind-blobs-16.png" "$sylva" render "$out/$kind.glb" --style blobs --clusters 16 \
      --size 1024 --ssaa 2 -o "$out/$kind-blobs-16.png"
    pic "$out/$kind-turntable-blobs.mp4" "$sylva" turntable "$out/$kind.glb" --style blobs \
      --clusters 16 --frames 96 --size 512 --keyframe-every 8 -q \
      --report "$out/$kind-turntable-blobs-coherence.csv" -o "$out/$kind-turntable-blobs.mp4"
  done
  # Hegeman et al.'s AO on a ground plane and a grass patch (Eq. 7-9).
  pic "$out/tree-ground-ao/" "$sylva" buffers "$out/tree.glb" --ground --elevation 35 --size 768 \
    --buffers ao --set ao.model=hegeman-sphere --out-dir "$out/tree-ground-ao"
  pic "$out/tree-ground-hegeman.png" "$sylva" render "$out/tree.glb" --ground --elevation 35 \
    --size 1024 --ssaa 2 --ambient 0.8 --set ao.model=hegeman-sphere \
    -o "$out/tree-ground-hegeman.png"
  run "$sylva" sample grass -o "$out/grass.glb"
  pic "$out/grass-ao/" "$sylva" buffers "$out/grass.glb" --elevation 30 --size 768 --buffers ao \
    --set ao.model=hegeman-sphere --out-dir "$out/grass-ao"
  run "$sylva" bake "$out/tree.glb" --cache-dir "$cache" -o "$out/tree-baked.glb"
  pic "$out/tree-baked-standard.png" "$sylva" render "$out/tree-baked.glb" --size 1024 --ssaa 2 \
    -o "$out/tree-baked-standard.png"
  pic "$out/bush-tradeoff.png" "$sylva" tradeoff "$out/bush.glb" --study foliage \
    --grids 32,64,128 -o "$out/bush-tradeoff.csv" --plot "$out/bush-tradeoff.png"
}

gallery
counting=0
echo "demo: $total pictures into $out/ (the commands' messages in $log)"
gallery
echo "demo: done in $(((SECONDS - start) / 60)):$(printf %02d $(((SECONDS - start) % 60))); \
the buffer previews are in $out/*-buffers/ and $out/*-normals-*/ (*.preview.png)"
