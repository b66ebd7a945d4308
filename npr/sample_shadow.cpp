#include "npr/sample_shadow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"

namespace sylva {

namespace {

// The texel coordinates (continuous, texel (i, j) centred at (i + 0.5, j + 0.5)) and the depth
// along the light of world point p; false behind the light.
bool to_light(const Camera& light, int size, const glm::vec3& p, glm::vec2& at, float& depth) {
  const glm::vec4 v = light.view * glm::vec4(p, 1.0f);
  const glm::vec4 clip = light.proj * v;
  if (!(clip.w > 0.0f)) return false;
  at = {(clip.x / clip.w * 0.5f + 0.5f) * float(size),
        (0.5f - clip.y / clip.w * 0.5f) * float(size)};
  depth = -v.z;
  return std::isfinite(at.x) && std::isfinite(at.y) && std::isfinite(depth);
}

// The samples are splatted in this many runs (each its own map, joined by their minimum).
constexpr int kShadowRuns = 8;

}  // namespace

SampleShadow sample_shadow_map(const SurfaceSamples& samples, const Sphere& sphere,
                               const glm::vec3& toward_light, bool point, int size, float reach) {
  SYLVA_CHECK(size >= 8 && !sphere.empty(), "sample_shadow_map: size >= 8 and a sphere");
  SampleShadow m;
  m.light = make_light_camera(sphere, toward_light, point, size);
  const float inf = std::numeric_limits<float>::infinity();
  // kShadowRuns runs of the samples splatted in parallel, each into its own map, then the
  // nearest of them (the same map in any order).
  std::vector<cv::Mat> runs(kShadowRuns);
  cv::parallel_for_(cv::Range(0, kShadowRuns), [&](const cv::Range& r) {
    for (int run = r.start; run < r.end; ++run) {
      cv::Mat depth(size, size, CV_32FC1, cv::Scalar(inf));
      const size_t end = samples.size() * size_t(run + 1) / kShadowRuns;
      for (size_t i = samples.size() * size_t(run) / kShadowRuns; i < end; ++i) {
        glm::vec2 at;
        float d;
        if (!to_light(m.light, size, samples.positions[i], at, d)) continue;
        const int x = int(std::floor(at.x)), y = int(std::floor(at.y));
        if (x < 0 || y < 0 || x >= size || y >= size) continue;
        float& t = depth.at<float>(y, x);
        t = std::min(t, d);
      }
      runs[size_t(run)] = depth;
    }
  });
  m.depth = runs[0];
  for (size_t run = 1; run < runs.size(); ++run)
    cv::min(m.depth, runs[run], m.depth);
  // Samples are about a texel apart: the nearest of 3 x 3 closes the holes between them.
  cv::erode(m.depth, m.depth, cv::Mat());
  const float texel = 2.0f * sphere.radius / float(size);
  m.bias = 2.0f * texel;
  m.reach = std::max(texel, reach * sphere.radius);
  return m;
}

float light_reaching(const SampleShadow& m, const glm::vec3& p) {
  if (m.empty()) return 1.0f;
  glm::vec2 at;
  float d;
  const int size = m.depth.cols;
  if (!to_light(m.light, size, p, at, d)) return 1.0f;
  // Bilinear between texel centres, so the light changes smoothly as the point moves; texels
  // with nothing in them count as the point's own depth (no occluder).
  const float fx = at.x - 0.5f, fy = at.y - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  float front = 0.0f;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, size - 1), y = std::clamp(y0 + dy, 0, size - 1);
      const float t = m.depth.at<float>(y, x);
      front += (dx ? ax : 1.0f - ax) * (dy ? ay : 1.0f - ay) * (std::isfinite(t) ? t : d);
    }
  const float behind = std::max(0.0f, d - front - m.bias);
  return std::exp(-behind / m.reach);
}

}  // namespace sylva
