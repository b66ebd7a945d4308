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

// The parts of `plant` (CV_8UC1) outside a crown `body` (CV_8UC1) and farther than detail / 2
// from it, in connected pieces (8-neighbours) that extend over >= 2 x detail: a willow's
// hanging strands, twigs, a fern's leaflets, drawn as centre lines. All 0 at detail < 2.
cv::Mat thin_parts(const cv::Mat& plant, const cv::Mat& body, double detail);

// The crown's shape at the scale of `detail` px from a continuous coverage (CV_32FC1 in [0, 1],
// e.g. passes/crown_coverage.h's 1 - exp(-density)): the coverage smoothed by a Gaussian of
// sigma = detail / 2, whose level set kCrownLevel is the outline. Where the coverage moves a
// little from one view to the next, so does this outline (a closing and opening of a binary
// mask jumps instead). At the level 0.2 it encloses the leaves: it lies about 0.4 x detail
// outside a solid edge, over the paper rather than over leaves that turn under it. Holes in the
// crown smaller than (2 x detail)² px² are filled and separate pieces of it smaller than (4 x
// detail)² px² removed (as thin parts, thin_parts draws them if they are long), since a gap
// that small is seen through the whole crown only from a few directions. The frame's edge is
// outside the crown, so a plant the frame cuts still gets a closed outline.
// field: the smoothed coverage, with the dropped holes and pieces set just past the level,
// so the outline snapped to it (snap_to_level) agrees with `body`. detail < 2: body =
// coverage >= kCrownLevel, no smoothing, nothing dropped.
struct CrownField {
  cv::Mat field;  // CV_32FC1
  cv::Mat body;   // CV_8UC1, 255 = inside (field >= kCrownLevel)
};
inline constexpr float kCrownLevel = 0.2f;
CrownField crown_field(const cv::Mat& coverage, double detail);

// Moves each point of `line` (continuous image coordinates of `field`, pixel (i, j) centred at
// (i + 0.5, j + 0.5)) onto the level set `level` of the bilinearly interpolated field by Newton
// steps along its gradient, so an outline traced on the pixel grid lies where the field
// crosses the level, to a fraction of a pixel; a point that would move more than `reach` px, or
// where the field is flat, stays.
void snap_to_level(std::vector<cv::Point2f>& line, const cv::Mat& field, float level, float reach);

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
