// Helpers shared by the image passes (DESIGN.md §2, passes/): resolution-independent sizes and
// the image conventions every pass follows. Images are row 0 at the top; masks and line
// coverage are CV_32FC1 in [0, 1]; colour images are CV_8UC4 BGRA sRGB with alpha = coverage,
// as the raster pass's colour target (core/gl/gbuffer.h).
#pragma once

#include <algorithm>
#include <functional>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace sylva {

// Sizes in pixels are given at a reference resolution (the shorter image side of 1024 px), so a
// 4096² render looks like a 1024² one: the factor to multiply them by for `size`.
inline constexpr int kReferenceResolution = 1024;
double reference_scale(const cv::Size& size);

// A programming error (SYLVA_CHECK) unless m has the given type and size (size empty = any):
// passes check the images the graph hands them once, at the top.
void expect_image(const cv::Mat& m, int type, const cv::Size& size, const char* what);

// The connected pieces (8-neighbours) of `mask` (CV_8UC1, non-zero = in) that `pick` takes, given
// each piece's row of cv::connectedComponentsWithStats (CC_STAT_LEFT ... CC_STAT_AREA):
// CV_8UC1, 255 on them.
cv::Mat pieces_where(const cv::Mat& mask, const std::function<bool(const int* stats)>& pick);

// The pairs (key, index) in the order std::sort gives them (by key, ties by index), sorted in
// linear time for keys in [0, 1]: a stable counting sort on 2^16 bins of the key, then a sort
// within each bin. Keys outside [0, 1] still sort right (their bins are clamped), only slower.
void sort_unit_keys(std::vector<std::pair<float, size_t>>& pairs);

// Normalised convolution: `weighted` (values times their weight, CV_32FC1) and `weight` (CV_32FC1,
// the same size) each blurred (Gaussian, sigma px, at least 0.5), the first divided by the second
// (at least 1e-6): the values averaged over where they are. The two blurs run side by side.
cv::Mat normalised_blur(const cv::Mat& weighted, const cv::Mat& weight, double sigma);

// 0 below e0, 1 above e1, Hermite-smooth between; a step at e1 when e1 <= e0.
inline float smoothstep(float e0, float e1, float x) {
  if (e1 <= e0) return x >= e1 ? 1.0f : 0.0f;
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Calls f(begin, end) for bands of [0, count) (image rows, or columns) in parallel through
// cv::parallel_for_, a few bands per thread (a band per row would cost each row the
// per-band set-up). Callers write only what their band owns and reduce nothing across bands,
// so the result does not depend on the number of threads or how the bands fall.
template <class F>
void for_bands(int count, F f) {
  const double bands = std::max(1, cv::getNumThreads()) * 4.0;
  cv::parallel_for_(
      cv::Range(0, count), [&](const cv::Range& r) { f(r.start, r.end); }, bands);
}

}  // namespace sylva
