// One wash of the watercolor pass (passes/watercolor.h) per leaf cluster ("layer"): the
// cluster's mask, blurred and thresholded (wet-on-wet or wet-on-dry edge), wobbled along the
// paper gradient, darkened along its rim where pigment pools, continued under the clusters in
// front of it by normalised convolution, tinted with the cluster's pigment, with leaf detail
// from the blurred depth test (Luft & Deussen), as optical density over its bounding box.
//
// Reads the frame's shared images (Shared: layer labels, display luminance, depth, wobble);
// writes the returned layer's density image. Layers are independent and may be painted in
// parallel; glazing them together (in a fixed order) is the caller's.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "passes/watercolor_common.h"
#include "passes/watercolor_textures.h"

namespace sylva::watercolor_internal {

// A leaf cluster's statistics over the frame (sums in one pass, then what derives from them).
struct Layer {
  int32_t id = 0;
  int count = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive bounding box
  float order_depth = 0;                 // what the layers are sorted by (back to front)
  // Where the wash's own paper lies: canvas position = image position - canvas (px). With
  // surface samples the cluster's projected centre less a seeded shift, so the wash carries
  // its grain and wobble as it moves; else 0 (the paper stays put under every wash).
  cv::Point2f canvas{0.0f, 0.0f};
  double sum_color[3] = {0, 0, 0};  // linear, premultiplied by coverage
  double sum_alpha = 0;
  double sum_pigment[3] = {0, 0, 0};  // albedo (linear, premultiplied) when it is the pigment
  double sum_pigment_alpha = 0;
  double sum_depth = 0, sum_depth2 = 0;
  // derived
  float mean_depth = 0, depth_spread = 0;
  cv::Vec3f mean_color, pigment;  // linear
  cv::Vec3f pigment_display;      // sRGB-encoded
  float mean_luminance = 0;       // display (sRGB-encoded) luminance
};

// A painter lays a thin wash where the foliage thins (a willow's curtain of strands, a crown's
// ragged edge) and a full one where it is dense: a leaf wash carries none of its pigment where
// the leaves' smoothed coverage is kThinCover (half the level at which the crown's parts begin,
// watercolor.cpp kPartLevel) and all of it from kFullCover on, fading between (smoothstep).
inline constexpr float kThinCover = 0.075f;
inline constexpr float kFullCover = 0.45f;

// The washes' masks are blurred at 1 / mask_factor of the resolution (smooth there), and the
// fields they are shaped by (the crown's parts, the leaves' coverage) are made at it too.
inline int mask_factor(float sigma) {
  return std::clamp(int(sigma / 2.0f), 1, 4);
}

struct Shared {
  cv::Size size;
  // CV_32SC1: index of the layer (back to front), -1 background: the washes' shapes. From the
  // scene's crown parts when there are surface samples, else the id buffer's.
  cv::Mat label;
  // CV_32SC1: the id buffer's layer index, where it differs from `label` (from the scene):
  // which layer's leaf a pixel shows, for the leaf detail. Empty: `label`.
  cv::Mat seen;
  cv::Mat luminance;  // CV_32FC1 display luminance of the un-premultiplied shaded colour
  cv::Mat depth;
  const PaperField* paper = nullptr;  // the paper the washes wobble along
  float wobble_gain = 0;              // px of displacement per unit of paper slope (0 = none)
  float max_wobble = 0;               // px, bound of each component of the displacement
  float sigma = 0;                    // px
  float half_width = 0.5f;            // of the threshold smoothstep
  float edge_gain = 0;                // d - 1 at the steepest edge, <= 1 (d = 2: twice the pigment)
  float detail = 0;
  // Where a wash's rim may darken (CV_8UC1, 255 = fully): along the foliage's outer edge and
  // where a nearer wash stands in front of a farther one by a depth step, not along every
  // border between neighbouring clusters. Empty: everywhere.
  cv::Mat rim_ok;
  // The shaded luminance smoothed over the plant at the washes' scale (CV_32FC1, display
  // values, at a quarter of the resolution: soft_at): the wet-in-wet gradation of value inside
  // a wash follows it by `gradation`.
  cv::Mat soft_luminance;
  // soft_luminance at image pixel (x, y) (sample_at).
  float soft_at(int x, int y) const { return sample_at(soft_luminance, size, x, y); }
  // The leaves' coverage smoothed at the washes' scale (CV_32FC1 in [0, 1], at a fraction of
  // the resolution: cover_at; watercolor_light.h foliage_cover), from the scene's samples; empty
  // without them. A leaf wash's pigment fades in from kThinCover to kFullCover of it.
  cv::Mat cover;
  float cover_at(int x, int y) const { return sample_at(cover, size, x, y); }
  float gradation = 0;
  float warm_cool = 0;  // watercolor.warm_cool: the lit side warmer, the shaded side cooler
  // Gaps in a mass's wash smaller than this (px; the closing's radius) are painted over where
  // they show the paper, as a painter lays a mass in one wash (0 = none; watercolor.mass).
  float close = 0;
  int32_t wood = 0;  // the wood's layer id, which is never closed (its gaps are the crown's)
  const SrgbTables* srgb = nullptr;
};

// Where a wash goes: it is glazed as it is painted, row by row, with no buffer of the wash
// itself (its optical density, -log2 transmittance, and its coverage in [0, 1]), over `density`
// (the glaze so far, CV_32FC3; with `weaken`, what lies behind is first
// weakened where the wash covers it, as under a nearer wash), and `bark` (the wood's wash over
// bark_roi, or empty) weakened alike.
struct GlazeInto {
  cv::Mat density;
  cv::Mat bark;
  cv::Rect bark_roi;
  bool weaken = true;
  cv::Point origin{0, 0};  // the image pixel at density's (0, 0)
};

// Layer `k` (its index back to front in Shared::label) painted over its bounding box, padded by
// the blur and the wobble, and glazed into `into`.
void paint_layer(const Shared& s, const Layer& layer, int k, GlazeInto& into);

// Every layer of `sorted` painted and glazed (their optical densities added, back to front):
// CV_32FC3 over the image. The wood's wash (layer id `wood`, 0 = none) lies under the leaves',
// which leave it bare where `wood_seen()` (CV_8UC1, 255 = wood; no function = none) shows it,
// asked for once the washes are painted.
cv::Mat glaze(const Shared& s, const std::vector<Layer>& sorted, int32_t wood,
              const std::function<cv::Mat()>& wood_seen);

}  // namespace sylva::watercolor_internal
