// Temporal coherence with the motion taken out (issue "Temporal coherence"; DESIGN.md §6):
// each plant pixel of frame i is carried to where the same surface point lies in frame i-1,
// with the renderer's own view-space positions and both frames' cameras, and compared there;
// pixels the other frame does not see (behind something, or off the frame) are left out by a
// depth test. A camera that does not move gives exactly 0.
//
// reprojection_error: the mean |difference| of B, G, R in 8-bit levels between frame i's pixel
// and frame i-1 sampled (bilinearly) at its reprojected place, over frame i's plant pixels that
// frame i-1 also sees (its depth at that place within 1 % of the reprojected depth).
// line_pop: of the line pixels that both frames see, the share with no line pixel of the other
// frame within 1.5 px of their reprojected place; the larger of the two directions (lines that
// vanish, and lines that appear). A line pixel beside the plant (an outline over the paper)
// moves as the plant pixel nearest to it does, and is seen where that one is.
//
// Reads, per frame: the style's image (CV_8UC4), the view-space positions (CV_32FC3, 0 =
// background), the line pixels (CV_8UC1, non-zero = line; may be empty) and the camera.
#pragma once

#include <opencv2/core.hpp>
#include <optional>

#include "core/gl/camera.h"

namespace sylva {

struct CoherenceFrame {
  cv::Mat image;     // CV_8UC4 BGRA
  cv::Mat position;  // CV_32FC3 view space, 0 on the background
  cv::Mat lines;     // CV_8UC1, non-zero = a line pixel; empty for styles without lines
  Camera camera;     // view, projection and size of the frame
};

struct FrameCoherence {
  double reprojection_error = 0.0;  // 8-bit levels
  std::optional<double> line_pop;   // share in [0, 1]; empty without lines in both frames
  size_t pixels = 0;                // plant pixels of `current` that `previous` sees
};

// Both frames of one size; a programming error (SYLVA_CHECK) otherwise.
FrameCoherence frame_coherence(const CoherenceFrame& previous, const CoherenceFrame& current);

}  // namespace sylva
