#include "npr/blob_shape.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sylva {

std::vector<glm::vec2> regional_centers(const std::vector<glm::vec2>& control_points,
                                        glm::vec2 center, int peaks) {
  const int n = static_cast<int>(control_points.size());
  std::vector<glm::vec2> out;
  if (n == 0) return out;
  peaks = std::clamp(peaks, 1, n);
  for (int k = 0; k < peaks; ++k) {
    const int a = k * n / peaks, b = (k + 1) * n / peaks;
    glm::dvec2 sum(0.0);
    for (int i = a; i < b; ++i)
      sum += glm::dvec2(control_points[static_cast<size_t>(i)]);
    out.push_back(0.5f * (glm::vec2(sum / static_cast<double>(b - a)) + center));
  }
  return out;
}

BlobShape make_blob_shape(const std::vector<glm::vec2>& control_points, glm::vec2 center, int peaks,
                          float height_fraction) {
  BlobShape s;
  s.center = center;
  s.peaks = regional_centers(control_points, center, peaks);
  double r = 0;
  for (const glm::vec2& p : control_points)
    r += glm::length(p - center);
  if (!control_points.empty()) r /= static_cast<double>(control_points.size());
  const float width = std::max(1.0f, static_cast<float>(2.0 * r));
  s.height = height_fraction * width;
  s.sigma = 0.25f * width;
  return s;
}

namespace {

// h and its gradient at p.
float height_and_gradient(const BlobShape& s, glm::vec2 p, glm::vec2* grad) {
  // h = H (1 - P), P = prod (1 - g_k); dh = H P sum_k dg_k / (1 - g_k), written without the
  // division: dh = H sum_k dg_k prod_{j != k} (1 - g_j).
  const float inv2s2 = 1.0f / (2.0f * s.sigma * s.sigma);
  const size_t n = s.peaks.size();
  float g[16], prod = 1.0f;
  glm::vec2 dg[16];
  SYLVA_CHECK(n <= 16, "blob_height: at most 16 peaks");
  for (size_t k = 0; k < n; ++k) {
    const glm::vec2 d = p - s.peaks[k];
    g[k] = std::exp(-glm::dot(d, d) * inv2s2);
    dg[k] = -2.0f * inv2s2 * g[k] * d;
    prod *= 1.0f - g[k];
  }
  if (grad) {
    glm::vec2 sum(0.0f);
    for (size_t k = 0; k < n; ++k) {
      float others = 1.0f;
      for (size_t j = 0; j < n; ++j)
        if (j != k) others *= 1.0f - g[j];
      sum += dg[k] * others;
    }
    *grad = s.height * sum;
  }
  return s.height * (1.0f - prod);
}

}  // namespace

float blob_height(const BlobShape& shape, glm::vec2 p) {
  return height_and_gradient(shape, p, nullptr);
}

glm::vec3 blob_normal(const BlobShape& shape, glm::vec2 p) {
  glm::vec2 g;
  height_and_gradient(shape, p, &g);
  // z = h(x, y_img); view y = -y_img, so dh/dy_view = -g.y.
  return glm::normalize(glm::vec3(-g.x, g.y, 1.0f));
}

}  // namespace sylva
