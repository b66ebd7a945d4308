#include "passes/watercolor_common.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/color.h"

namespace sylva::watercolor_internal {

namespace {

float srgb_encode_exact(float l) {
  return linear_to_srgb(l);
}
float srgb_decode_exact(float c) {
  return srgb_to_linear(c);
}

}  // namespace

const SrgbTables& srgb_tables() {
  static const SrgbTables t = [] {
    SrgbTables s;
    for (int i = 0; i < 256; ++i)
      s.to_linear[size_t(i)] = srgb_decode_exact(float(i) / 255.0f);
    s.from_linear.resize(kEncodeSize + 1);
    for (int i = 0; i <= kEncodeSize; ++i) {
      const float c = srgb_encode_exact(float(i) / float(kEncodeSize));
      s.from_linear[size_t(i)] = uint8_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
    }
    s.encode.resize(kCurveSize + 2);
    s.decode.resize(kCurveSize + 2);
    for (int i = 0; i <= kCurveSize + 1; ++i) {
      const float v = std::min(1.0f, float(i) / float(kCurveSize));
      s.encode[size_t(i)] = srgb_encode_exact(v);
      s.decode[size_t(i)] = srgb_decode_exact(v);
    }
    s.density.resize(kCurveSize + 2);
    for (int i = 0; i <= kCurveSize + 1; ++i) {
      const float l = s.decode[size_t(i)];
      s.density[size_t(i)] = l > 0.0f ? std::min(kMaxDensity, -std::log2(l)) : kMaxDensity;
    }
    return s;
  }();
  return t;
}

cv::Mat blur(const cv::Mat& m, float sigma) {
  if (sigma < 0.3f) return m.clone();
  cv::Mat out;
  cv::GaussianBlur(m, out, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace sylva::watercolor_internal
