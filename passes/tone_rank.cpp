#include "passes/tone_rank.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "passes/pass_common.h"

namespace sylva {

namespace {

// The least smoothing (px at the coarser size) tone_rank smooths at half the working size for.
constexpr double kLeastCoarseSigma = 1.5;

// 1 - the Rec. 709 luma of a BGRA pixel's sRGB-encoded values: the tone as the eye reads it.
float darkness_of(const cv::Vec4b& c) {
  const float luma = (0.0722f * c[0] + 0.7152f * c[1] + 0.2126f * c[2]) / 255.0f;
  return std::clamp(1.0f - luma, 0.0f, 1.0f);
}

}  // namespace

cv::Mat tone_darkness(const cv::Mat& color) {
  expect_image(color, CV_8UC4, {}, "color");
  cv::Mat dark(color.size(), CV_32FC1, cv::Scalar(0));
  for_bands(color.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const cv::Vec4b* c = color.ptr<cv::Vec4b>(y);
      float* d = dark.ptr<float>(y);
      for (int x = 0; x < color.cols; ++x)
        if (c[x][3] >= 128) d[x] = darkness_of(c[x]);
    }
  });
  return dark;
}

namespace {

// tone_darkness and the plant's coverage (1 where alpha >= 128) as the two channels of one
// CV_32FC2 image, made in one pass.
cv::Mat darkness_and_cover(const cv::Mat& color) {
  expect_image(color, CV_8UC4, {}, "color");
  cv::Mat out(color.size(), CV_32FC2);
  for_bands(color.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const cv::Vec4b* c = color.ptr<cv::Vec4b>(y);
      cv::Vec2f* o = out.ptr<cv::Vec2f>(y);
      for (int x = 0; x < color.cols; ++x)
        o[x] = c[x][3] < 128 ? cv::Vec2f(0.0f, 0.0f) : cv::Vec2f(darkness_of(c[x]), 1.0f);
    }
  });
  return out;
}

}  // namespace

ToneRank tone_rank(const cv::Mat& color, cv::Size size, double sigma, bool ranked) {
  cv::Mat both = darkness_and_cover(color);
  // Area-averaged to the working size, both channels at once.
  if (size != color.size()) cv::resize(both, both, size, 0, 0, cv::INTER_AREA);
  cv::Mat channels[2];
  cv::split(both, channels);
  const cv::Mat &dark = channels[0], &cover = channels[1];
  ToneRank t;
  t.plant = cover >= 0.5f;
  if (cv::countNonZero(t.plant) == 0) return {};
  t.darkness = dark;
  if (!ranked && sigma >= 2.0 * kLeastCoarseSigma) {
    // Read only at points: smoothed at half the working size, a quarter of the work, where a
    // Gaussian this wide loses nothing (dark_near reads it bilinearly).
    cv::Mat half[2];
    cv::resize(both, both, {(size.width + 1) / 2, (size.height + 1) / 2}, 0, 0, cv::INTER_AREA);
    cv::split(both, half);
    t.dark = normalised_blur(half[0], half[1], 0.5 * sigma);
    return t;
  }
  // The plant's darkness only: divide out the paper's share of each pixel and of the blur.
  t.dark = normalised_blur(dark, cover, sigma);
  if (!ranked) return t;
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      if (t.plant.at<uint8_t>(y, x)) t.sorted.push_back(t.dark.at<float>(y, x));
  std::sort(t.sorted.begin(), t.sorted.end());
  return t;
}

float ToneRank::rank_of(float v) const {
  if (sorted.empty()) return 0.0f;
  // Mid-rank of v among the values: ties share the middle of their run.
  const auto lo = std::lower_bound(sorted.begin(), sorted.end(), v);
  const auto hi = std::upper_bound(lo, sorted.end(), v);
  return float((double(lo - sorted.begin()) + 0.5 * double(hi - lo)) / double(sorted.size()));
}

float ToneRank::dark_near(cv::Point2f at) const {
  if (dark.empty()) return 0.0f;
  if (dark.size() == plant.size()) {
    const int x = std::clamp(int(std::floor(at.x)), 0, dark.cols - 1),
              y = std::clamp(int(std::floor(at.y)), 0, dark.rows - 1);
    return dark.at<float>(y, x);
  }
  // Smoothed at a coarser size: bilinear between its pixels' centres, clamped to the image.
  const float u = std::clamp(at.x * float(dark.cols) / float(plant.cols) - 0.5f, 0.0f,
                             float(dark.cols - 1)),
              v = std::clamp(at.y * float(dark.rows) / float(plant.rows) - 0.5f, 0.0f,
                             float(dark.rows - 1));
  const int x0 = int(u), y0 = int(v), x1 = std::min(x0 + 1, dark.cols - 1),
            y1 = std::min(y0 + 1, dark.rows - 1);
  const float fx = u - float(x0), fy = v - float(y0);
  const float top = dark.at<float>(y0, x0) + fx * (dark.at<float>(y0, x1) - dark.at<float>(y0, x0));
  const float bottom =
      dark.at<float>(y1, x0) + fx * (dark.at<float>(y1, x1) - dark.at<float>(y1, x0));
  return top + fy * (bottom - top);
}

float ToneRank::rank_near(cv::Point2f at) const {
  return rank_of(dark_near(at));
}

}  // namespace sylva
