// Shrink-wrapping a leaf cluster in image space (Dudley 2005 §4.2.1): N control points on a
// circle around the cluster's pixels are each moved a fixed fraction of the way toward the
// cluster's centre, again and again, until they land on one of its pixels; then back toward
// where they came from, to the edge of the cluster's pixels on the way (bisection), so a point
// moves with the edge when the pixels change a little rather than by whole steps (issue
// "Temporal coherence"). A closed cubic B-spline through them (npr/bspline.h) is the blob's
// outline.
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <vector>

namespace sylva {

struct ShrinkWrapParams {
  // Control points on the outline; more follow the leaves more closely (Dudley Fig. 7.3).
  // [3, 512]; default 20.
  int control_points = 20;
  // Fraction of the remaining distance to the centre a point moves per step; small steps stop
  // at the first leaf pixel on the way in, large ones overshoot into the cluster. (0, 1];
  // default 0.2 (Dudley's 20 %).
  float step = 0.2f;
};

// Throws InputError(where + ".control_points" / ".step", ...) outside the ranges above.
void validate_shrink_wrap(const ShrinkWrapParams& p, const char* where);

struct ShrinkWrap {
  // Coordinates in pixels of the mask: pixel (x, y) covers [x, x + 1) x [y, y + 1).
  glm::vec2 center{0.0f};         // mean of the cluster's pixel centres
  float radius = 0;               // start circle: farthest pixel centre + 1 px
  std::vector<glm::vec2> points;  // control points; point i starts at angle 2 pi i / N
                                  // clockwise on screen from straight up
  bool empty() const { return points.empty(); }
};

// Shrink-wraps the non-zero pixels of `mask` (CV_8UC1). Every returned point lies in a mask
// pixel, within 1/64 of its last step of the pixel's edge it crossed: a point that reaches the
// centre (within half a pixel) without meeting one is placed on the cluster pixel nearest the
// centre (a ring-shaped cluster's centre is not on a leaf). An all-zero mask gives an empty result.
ShrinkWrap shrink_wrap(const cv::Mat& mask, const ShrinkWrapParams& params);

}  // namespace sylva
