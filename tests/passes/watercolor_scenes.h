// Synthetic G-buffers for the watercolor tests (test_watercolor.cpp) and the look images
// (tests/look): discs, leaf clumps and rectangles of one id each, with view-space positions.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "passes/watercolor.h"

namespace sylva::test {

// A synthetic G-buffer: pinhole camera (focal f px, principal point at the centre), positions
// in view space (camera looks along -Z), depth = -z.
struct WatercolorScene {
  WatercolorImages img;
  float focal = 0;
};

float srgb_encode(float linear);  // linear (clamped to [0, 1]) -> sRGB in [0, 1]
WatercolorScene empty_scene(cv::Size size);
void set_pixel(WatercolorScene& s, int x, int y, int32_t id, cv::Vec3f bgr_linear, float depth);
// A disc of one id, its depth bulging towards the viewer like a sphere of leaves.
void add_disc(WatercolorScene& s, cv::Point2f centre, float radius, int32_t id, cv::Vec3f bgr,
              float depth);
// A clump of small leaves (ellipses) around a centre: per-leaf shading and depth jitter, so
// the clusters have the detail a real render has.
void add_clump(WatercolorScene& s, cv::RNG& rng, cv::Point2f centre, float radius, int32_t id,
               cv::Vec3f bgr, float depth, int leaves, float leaf_size);
void add_rect(WatercolorScene& s, cv::Rect r, int32_t id, cv::Vec3f bgr, float depth);
// A tree of `clusters` leaf clumps over a trunk and two limbs (id 1000), seeded.
WatercolorScene synthetic_tree(cv::Size size, int clusters, int leaves_per_cluster, uint64_t seed);

}  // namespace sylva::test
