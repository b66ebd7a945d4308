// The measures of the ink acceptance tests (issue "Ink for illustrators"), on rendered images:
// which pixels are ink, how much of the plant they cover, whether the plant's outline is drawn,
// whether two resolutions draw the same lines, and where the pen's tone falls.
#pragma once

#include <opencv2/core.hpp>

namespace sylva::test {

// Ink pixels of an opaque drawing on light paper: luminance below half (CV_8UC1, 255 = ink).
cv::Mat ink_pixels(const cv::Mat& bgr_or_bgra);

// The plant's pixels of a render with a transparent background: alpha >= 128.
cv::Mat plant_pixels(const cv::Mat& bgra);

// Share of `of`'s pixels within `distance` px of a pixel of `near` (both CV_8UC1 masks).
double share_near(const cv::Mat& of, const cv::Mat& near, double distance);

// The plant's outline: its mask closed and then opened by a disc of diameter `disc` px, and
// the share of that outline's pixels within `distance` px of ink.
double outline_drawn(const cv::Mat& plant, const cv::Mat& ink, double disc, double distance);

// Ink density (share of ink pixels) in the darkest and the brightest third of the plant's
// pixels by `luminance` (CV_32FC1 or CV_8UC*), blurred by a Gaussian of sigma `blur` px first.
struct ToneThirds {
  double dark = 0, bright = 0;
};
ToneThirds ink_by_tone(const cv::Mat& ink, const cv::Mat& plant, const cv::Mat& luminance,
                       double blur);

}  // namespace sylva::test
