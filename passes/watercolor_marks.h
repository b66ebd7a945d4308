// The watercolor's detail layer (issue "Watercolor that paints the tree as a painter would",
// Luft & Deussen 2006's leaf detail): leaf-scale marks glazed over the washes. Every leaf piece
// of the scene (npr/leaf_pieces.h), merged into clumps of about the mark's size, becomes a dab
// of its own projected shape (passes/leaf_primitives.h: a willow's leaves and a pine's needles
// long, broad leaves round), at least watercolor.mark_size across, in its own shaded colour.
// A dab shows where it is the front one (a z-buffer of the dabs, the wood seen in front of
// them) and by Luft & Deussen's blurred depth test: one standing in front of the crown's
// blurred depth shows fully, one behind it fades out over a band of depth, so inner leaves
// melt into the wash instead of popping as the view turns. Dabs are denser in shadow: their
// pigment grows with the plant's tone rank (passes/tone_rank.h) and the key light's shadow
// through the crown (npr/sample_shadow.h), so the marks carry the light as a painter's darker
// touches do, and the species' character (strands, tiers, fronds) shows where the washes
// simplify it. Each dab is lighter at its edge than at its heart (a soft, wet touch) and
// carries a little more or less pigment than its neighbours, seeded by its place in the scene,
// so neighbouring dabs read as touches rather than one flat wash. Everything is anchored to
// the scene: the dabs move with it.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "core/gl/camera.h"
#include "npr/leaf_pieces.h"
#include "passes/leaf_primitives.h"
#include "passes/watercolor.h"

namespace sylva {

struct WatercolorMarkImages {
  std::shared_ptr<const LeafPieces> pieces;
  Camera camera;  // the frame's
  cv::Mat color;  // CV_8UC4 BGRA sRGB shaded, alpha = coverage: the dabs' colour and tone
  cv::Mat id;     // CV_32SC1: where the wood is seen (wood_cluster), which the dabs leave bare
  uint32_t wood_cluster = 0;
  double units_per_px = 0.0;  // scene units per px at the plant's distance (the clumps' cell)
  std::shared_ptr<const SurfaceSamples> samples;  // the key light's shadow map, or null
  KeyLight light;
};

struct WatercolorMarkParams {
  float strength = 0.6f;  // watercolor.marks, [0, 1]: the dabs' pigment (0 = no detail layer)
  float size = 10.0f;     // watercolor.mark_size, px at 1024 px, [2, 64]: the smallest dab
};

// The detail layer glazed into `density` (the washes' optical density, CV_32FC3, -log2
// transmittance per channel, the colour image's size): on bare paper the dabs' pigment, inside
// a wash their departure from their own local mean (touches that do not shift the wash's
// value). Nothing when strength is 0 or there are no pieces.
void glaze_marks(const WatercolorMarkImages& in, const WatercolorMarkParams& p, cv::Mat& density);

// The same from the watercolor's images and parameters (watercolor.marks, watercolor.mark_size);
// nothing without in.pieces.
void glaze_leaf_marks(const WatercolorImages& in, const WatercolorParams& p, cv::Mat& density);

}  // namespace sylva
