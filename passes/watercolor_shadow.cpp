#include "passes/watercolor_shadow.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "npr/sample_shadow.h"
#include "passes/pass_common.h"
#include "passes/watercolor_common.h"

namespace sylva::watercolor_internal {

namespace {

// The glaze's optical density per channel in full shadow at strength 1 (a neutral glaze of
// transmittance 2^-1, a half), and the cool glaze's display colour (BGR,
// ultramarine-violet), scaled to the same total density.
constexpr float kGlazeDensity = 1.0f;
const cv::Vec3f kCoolGlaze(0.80f, 0.62f, 0.56f);
// How deep the key light reaches into the crown, as a share of the scene's radius (it falls to
// 1/e over it behind the first leaves): a painter's shadow side is the crown's far half.
constexpr float kReach = 0.3f;

// The glaze's per-channel density at warm_cool `w`.
cv::Vec3f glaze_colour(float w) {
  const SrgbTables& srgb = srgb_tables();
  cv::Vec3f cool;
  for (int c = 0; c < 3; ++c)
    cool[c] = to_density(srgb, kCoolGlaze[c]);
  cool *= 3.0f * kGlazeDensity / (cool[0] + cool[1] + cool[2]);
  const cv::Vec3f neutral(kGlazeDensity, kGlazeDensity, kGlazeDensity);
  return (1.0f - w) * neutral + w * cool;
}

}  // namespace

cv::Mat key_shadow(const ViewPositions& view, const glm::mat4& view_to_world,
                   const SurfaceSamples& samples, const KeyLight& light, int cell, float sigma) {
  if (!light.on || light.sphere.empty() || samples.size() == 0) return {};
  const SampleShadow map =
      sample_shadow_map(samples, light.sphere, light.toward, light.point, kShadowMapSize, kReach);
  const CellPositions cells = cell_positions(view, cell);
  const cv::Mat& small_cover = cells.cover;
  cv::Mat shade(small_cover.size(), CV_32F, cv::Scalar(0));
  for (int y = 0; y < shade.rows; ++y) {
    const float* c = small_cover.ptr<float>(y);
    const cv::Vec3f* q = cells.mean.ptr<cv::Vec3f>(y);
    float* s = shade.ptr<float>(y);
    for (int x = 0; x < shade.cols; ++x) {
      if (!(c[x] > 0.0f)) continue;
      const glm::vec3 world(view_to_world * glm::vec4(q[x][0], q[x][1], q[x][2], 1.0f));
      s[x] = c[x] * (1.0f - light_reaching(map, world));
    }
  }
  // Soft: blurred over the plant's cells only (normalised convolution).
  const float small_sigma = std::max(1.0f, sigma / float(cell));
  cv::Mat out;
  cv::divide(blur(shade, small_sigma), cv::max(blur(small_cover, small_sigma), 1e-4), out);
  return out;
}

void glaze_shadow(const cv::Mat& shadow, float strength, float warm_cool, cv::Mat& density) {
  if (shadow.empty() || !(strength > 0.0f)) return;
  const cv::Vec3f glaze = strength * glaze_colour(warm_cool);
  const float fx = float(shadow.cols) / float(density.cols);
  const float fy = float(shadow.rows) / float(density.rows);
  for_bands(density.rows, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      cv::Vec3f* d = density.ptr<cv::Vec3f>(y);
      const float sy = (float(y) + 0.5f) * fy - 0.5f;
      for (int x = 0; x < density.cols; ++x) {
        const float cover = wash_cover(d[x]);
        if (cover <= 0.0f) continue;
        const float s = sample(shadow, (float(x) + 0.5f) * fx - 0.5f, sy);
        d[x] += (cover * std::clamp(s, 0.0f, 1.0f)) * glaze;
      }
    }
  });
}

}  // namespace sylva::watercolor_internal
