// The watercolor pass's light and structure fields (passes/watercolor.h): where rims may darken,
// the light a wash's gradation follows, and where the wood is seen.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/gl/camera.h"
#include "npr/surface_samples.h"
#include "passes/watercolor_layers.h"

namespace sylva::watercolor_internal {

// Shared::rim_ok for the layers `sorted` (back to front, Shared::label indexing them): 255 within
// reach of the blur and wobble of the foliage's outer edge or of a border between two washes
// whose order depths differ by more than rim_step (in [0, 1]) of their depth range, fading to 0
// beyond (CV_8UC1).
cv::Mat rim_allowed(const Shared& s, const std::vector<Layer>& sorted, float rim_step);

// Shared::soft_luminance: Shared::luminance averaged over the `covered` pixels (CV_8UC1
// non-zero) only, with a Gaussian of twice the wash blur (at least 3 px), at a quarter of the
// image's resolution (the grid rounds up; Shared::soft_at reads it).
cv::Mat smoothed_luminance(const Shared& s, const cv::Mat& covered);

// Where the id buffer (CV_32SC1) shows the wood cluster at least 5 px wide at 1024 px (`scale`
// = the image's size over 1024, reference_scale: the same width at every size), in pieces of at
// least 60 px at 1024 px, softened by 0.7 px: CV_8UC1, 255 = wood.
cv::Mat seen_wood(const cv::Mat& id, uint32_t wood_cluster, double scale);

// Shared::cover: the leaves' coverage (passes/crown_coverage.h crown_coverage, the `wood`
// cluster's samples left out) smoothed by a Gaussian of `sigma` px, at 1 / f of the resolution
// (mask_factor; Shared::cover_at reads it): where the foliage thins, its wash thins with it
// (watercolor_layers.h kThinCover, kFullCover).
cv::Mat foliage_cover(const SurfaceSamples& samples, const Camera& camera, cv::Size size, int f,
                      float sigma, uint32_t wood);

}  // namespace sylva::watercolor_internal
