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

namespace {

// Pixel centres of a w x h image unprojected at a linear view depth: inverse(proj) applied to
// (x_ndc, y_ndc, z_ndc, 1) is linear in x_ndc and y_ndc, so each row adds a step per pixel to
// the points on the near (z_ndc = -1) and far (z_ndc = 1) planes; the point is where the ray
// between them reaches view z = -depth.
class Unprojector {
 public:
  Unprojector(const glm::mat4& proj, cv::Size size) : m_inv(glm::inverse(proj)) {
    m_step_x = m_inv[0] * (2.0f / float(size.width));
    m_step_y = m_inv[1] * (-2.0f / float(size.height));
    m_first = m_inv * glm::vec4(1.0f / float(size.width) - 1.0f, 1.0f - 1.0f / float(size.height),
                                0.0f, 1.0f);
  }
  cv::Vec3f at(int x, int y, float depth) const {
    const glm::vec4 centre = m_first + float(x) * m_step_x + float(y) * m_step_y;
    const glm::vec3 n = glm::vec3(centre - m_inv[2]) / (centre.w - m_inv[2].w);
    const glm::vec3 f = glm::vec3(centre + m_inv[2]) / (centre.w + m_inv[2].w);
    const float dz = f.z - n.z;
    const float t = std::abs(dz) > 1e-20f ? (-depth - n.z) / dz : 0.0f;
    const glm::vec3 p = n + t * (f - n);
    return {p.x, p.y, p.z};
  }

 private:
  glm::mat4 m_inv;
  glm::vec4 m_first, m_step_x, m_step_y;
};

}  // namespace

CellPositions cell_positions(const ViewPositions& view, int cell) {
  const cv::Mat& depth = view.depth;
  const bool buffer = !view.position.empty();
  const Unprojector unproject(view.proj, depth.size());
  const cv::Size grid((depth.cols + cell - 1) / cell, (depth.rows + cell - 1) / cell);
  CellPositions out;
  out.mean = cv::Mat(grid, CV_32FC3, cv::Scalar::all(0));
  out.cover = cv::Mat(grid, CV_32FC1, cv::Scalar(0));
  cv::Mat count(grid, CV_32FC1, cv::Scalar(0));
  for (int y = 0; y < depth.rows; ++y) {
    const float* d = depth.ptr<float>(y);
    const cv::Vec3f* p = buffer ? view.position.ptr<cv::Vec3f>(y) : nullptr;
    cv::Vec3f* m = out.mean.ptr<cv::Vec3f>(y / cell);
    float* c = out.cover.ptr<float>(y / cell);
    float* n = count.ptr<float>(y / cell);
    for (int x = 0; x < depth.cols; ++x) {
      n[x / cell] += 1.0f;
      if (d[x] > 0.0f) {
        m[x / cell] += p ? p[x] : unproject.at(x, y, d[x]);
        c[x / cell] += 1.0f;
      }
    }
  }
  for (int y = 0; y < grid.height; ++y) {
    cv::Vec3f* m = out.mean.ptr<cv::Vec3f>(y);
    float* c = out.cover.ptr<float>(y);
    const float* n = count.ptr<float>(y);
    for (int x = 0; x < grid.width; ++x) {
      if (c[x] > 0.0f) m[x] /= c[x];
      c[x] /= n[x];
    }
  }
  return out;
}

}  // namespace sylva::watercolor_internal
