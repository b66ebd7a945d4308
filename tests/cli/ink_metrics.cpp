#include "tests/cli/ink_metrics.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace sylva::test {

cv::Mat ink_pixels(const cv::Mat& image) {
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey < 128;
}

cv::Mat plant_pixels(const cv::Mat& bgra) {
  cv::Mat alpha;
  cv::extractChannel(bgra, alpha, 3);
  return alpha >= 128;
}

double share_near(const cv::Mat& of, const cv::Mat& near, double distance) {
  const int total = cv::countNonZero(of);
  if (total == 0) return 1.0;
  cv::Mat dist;
  cv::distanceTransform(~near, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return double(cv::countNonZero((dist <= distance) & of)) / total;
}

double outline_drawn(const cv::Mat& plant, const cv::Mat& ink, double disc, double distance) {
  const int k = std::max(1, int(disc)) | 1;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
  cv::Mat shape;
  cv::morphologyEx(plant, shape, cv::MORPH_CLOSE, kernel, {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  cv::morphologyEx(shape, shape, cv::MORPH_OPEN, kernel, {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat inner;
  cv::erode(shape, inner, cv::Mat(), {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
  return share_near(shape & ~inner, ink, distance);
}

ToneThirds ink_by_tone(const cv::Mat& ink, const cv::Mat& plant, const cv::Mat& luminance,
                       double blur) {
  cv::Mat lum;
  if (luminance.channels() > 1)
    cv::cvtColor(luminance, lum,
                 luminance.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  else
    lum = luminance;
  lum.convertTo(lum, CV_32F);
  cv::Mat mask, num, den;
  plant.convertTo(mask, CV_32F, 1.0 / 255.0);
  cv::GaussianBlur(lum.mul(mask), num, {0, 0}, blur);
  cv::GaussianBlur(mask, den, {0, 0}, blur);
  std::vector<float> values;
  for (int y = 0; y < plant.rows; ++y)
    for (int x = 0; x < plant.cols; ++x)
      if (plant.at<uint8_t>(y, x)) values.push_back(num.at<float>(y, x) / den.at<float>(y, x));
  ToneThirds t;
  if (values.empty()) return t;
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const float low = sorted[sorted.size() / 3], high = sorted[2 * sorted.size() / 3];
  size_t i = 0, n_dark = 0, n_bright = 0, ink_dark = 0, ink_bright = 0;
  for (int y = 0; y < plant.rows; ++y)
    for (int x = 0; x < plant.cols; ++x) {
      if (!plant.at<uint8_t>(y, x)) continue;
      const float v = values[i++];
      const bool is_ink = ink.at<uint8_t>(y, x) != 0;
      if (v <= low) {
        ++n_dark;
        ink_dark += is_ink;
      } else if (v >= high) {
        ++n_bright;
        ink_bright += is_ink;
      }
    }
  t.dark = n_dark ? double(ink_dark) / n_dark : 0.0;
  t.bright = n_bright ? double(ink_bright) / n_bright : 0.0;
  return t;
}

}  // namespace sylva::test
