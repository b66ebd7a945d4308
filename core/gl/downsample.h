// SSAA down-sampling of the raster pass's images by an integer factor, one rule per kind of
// buffer. A factor x factor block of samples becomes one pixel:
// - colour (CV_8UC4 BGRA, sRGB): box average of all samples, background included, in linear
//   light (decode, average, re-encode); alpha is averaged linearly, so it is the coverage.
// - normal, depth, position, ka (CV_32FC1/3): average of the *covered* samples only (coverage
//   from the depth attachment), normals re-normalised; a pixel with no covered sample stays
//   0 (background). A pixel with any covered sample counts as covered, so these buffers
//   agree with the id buffer on which pixels are geometry.
// - id (CV_32SC1): the most frequent non-zero id of the block (ties: the first in raster
//   order); 0 only when no sample is covered. Ids are never blended into values that were
//   not rendered.
#pragma once

#include <opencv2/core.hpp>

namespace sylva {

// factor: samples per axis, [1, 4]; the input size must be a multiple of it. factor 1
// returns the input unchanged (shared data).
cv::Mat downsample_color(const cv::Mat& bgra_srgb, int factor);
// coverage: CV_8UC1 at the input's size, non-zero where a sample is geometry.
cv::Mat downsample_covered(const cv::Mat& values, const cv::Mat& coverage, int factor,
                           bool renormalize);
cv::Mat downsample_id(const cv::Mat& ids, int factor);

}  // namespace sylva
