// Every parameter a style preset can set (styles/presets/*.toml, --set key=value), as one
// struct bound to dotted keys by bind_style_params: style.* (what the raster pass draws) and
// foliage.* (the Luft preprocessing), ao.* (ambient occlusion), and one section per image pass
// (toon.*, ...).
#pragma once

#include <string>

#include "core/params.h"
#include "npr/ao_pass.h"
#include "npr/illumination_pass.h"
#include "passes/blobs.h"
#include "passes/composite.h"
#include "passes/edges.h"
#include "passes/hatching.h"
#include "passes/ink_lines.h"
#include "passes/leaf_primitives.h"
#include "passes/toon.h"
#include "passes/watercolor.h"

namespace sylva {

// style.albedo: what the albedo buffer holds.
enum class AlbedoSource {
  Textured,  // the textures' texels
  Flat,      // each texture's mean (flat tones)
};

struct StyleParams {
  // style.normals: the normals the raster pass draws with: original, realigned (Luft §3.3),
  // realigned-scaled (their length is ka, Luft Fig. 7c).
  NormalMode normals = NormalMode::Original;
  AlbedoSource albedo = AlbedoSource::Textured;  // style.albedo
  FoliageSettings foliage;
  AoSettings ao;  // ao.*: ambient occlusion (npr/ao_pass.h)
  EdgeParams edges;
  InkParams ink;
  InkLineParams lines;  // ink.detail and lines.*: the ink style's line hierarchy
  LeafParams leaves;    // leaves.*: the foliage's drawing primitives (ink, pen)
  PenParams pen;        // pen.*: tone drawn with strokes (the pen preset)
  ToonParams toon;
  WatercolorParams watercolor;
  BlobParams blobs;
};

// `set` refers into `params`: keep both alive together.
void bind_style_params(ParamSet& set, StyleParams& params);

}  // namespace sylva
