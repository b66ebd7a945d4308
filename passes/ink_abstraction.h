// The picture-scale abstraction of the ink lines (passes/ink_lines.h): the plant's coverage
// simplified to the smallest feature drawn, and the depth with features below that size
// filtered out. Both work on whole images with OpenCV's morphology and median filters, so they
// cost the same for 1,000 leaves as for 100,000.
//
// Reads the plant's coverage (CV_8UC1, non-zero = plant) and its linear depth (CV_32FC1, 0 =
// background); writes the images below at the same size.
#pragma once

#include <opencv2/core.hpp>

namespace sylva {

// The plant's shape at the scale of `detail` px. body: the coverage closed, then opened, by a
// disc of diameter `detail` (gaps and bumps smaller than it vanish); thin: the parts the
// opening removes whose connected piece extends over >= 2 x detail (a hanging strand, a twig,
// a leaflet), which are drawn as centre lines. Both CV_8UC1, 255 = inside. detail < 2: body =
// the coverage as it is, thin empty (all 0).
struct CrownShape {
  cv::Mat body, thin;
};
CrownShape crown_shape(const cv::Mat& plant, double detail);

// The depth median-filtered over a square window of about `window` px (odd, >= 3), quantised
// to 254 levels over the plant's depth range: CV_8UC1, level 1 + 253 (z - near) / (far -
// near), 255 where the window's median is background (most of it off the plant). near/far
// receive the plant's depth range (both 0 when it covers no pixel).
cv::Mat median_depth(const cv::Mat& depth, const cv::Mat& plant, double window, float& near,
                     float& far);
inline constexpr uint8_t kNoDepth = 255;

// Crown parts as regions: each non-zero label (CV_32SC1, e.g. leaf clusters) replaced by the
// most frequent non-zero label within `radius` px (a tie keeps the pixel's own, else the
// smaller label), so the parts' borders are smooth at that scale instead of following leaves.
// 0 stays 0.
cv::Mat majority_labels(const cv::Mat& labels, int radius);

}  // namespace sylva
