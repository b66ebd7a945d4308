#include "passes/watercolor_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "passes/crown_coverage.h"
#include "passes/pass_common.h"

namespace sylva::watercolor_internal {

// The narrowest wood the watercolor paints where it is seen, px at 1024 px.
constexpr double kSeenWoodWidth = 5.0;
// The least area of a piece of it, px at 1024 px: a branch, not the spot where a twig turns
// towards the view for a few pixels.
constexpr double kLeastWoodArea = 60.0;

// Where rims may darken (Shared::rim_ok): within reach of the wash's blur and wobble of the
// foliage's outer edge, or of a border between two washes whose depths differ by more than
// rim_step of the plant's depth extent.
cv::Mat rim_allowed(const Shared& s, const std::vector<Layer>& sorted, float rim_step) {
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  for (const Layer& L : sorted)
    lo = std::min(lo, L.order_depth), hi = std::max(hi, L.order_depth);
  const float step = rim_step * std::max(hi - lo, 0.0f);
  auto stepped = [&](int32_t a, int32_t b) {
    if (a == b) return false;
    if (a < 0 || b < 0) return true;
    return std::abs(sorted[size_t(a)].order_depth - sorted[size_t(b)].order_depth) > step;
  };
  cv::Mat free(s.size, CV_8U, cv::Scalar(255));  // 0 on a rim-making border
  for (int y = 0; y < s.size.height; ++y) {
    const int32_t* l = s.label.ptr<int32_t>(y);
    const int32_t* below = s.label.ptr<int32_t>(std::min(y + 1, s.size.height - 1));
    uint8_t* f = free.ptr<uint8_t>(y);
    uint8_t* fb = free.ptr<uint8_t>(std::min(y + 1, s.size.height - 1));
    for (int x = 0; x < s.size.width; ++x) {
      const int xr = std::min(x + 1, s.size.width - 1);
      if (stepped(l[x], l[xr])) f[x] = f[xr] = 0;
      if (stepped(l[x], below[x])) f[x] = fb[x] = 0;
    }
  }
  cv::Mat dist;
  cv::distanceTransform(free, dist, cv::DIST_L2, 3);
  const float reach = 2.0f * s.sigma + s.max_wobble + 2.0f;
  cv::Mat out(s.size, CV_8U);
  for (int y = 0; y < s.size.height; ++y) {
    const float* d = dist.ptr<float>(y);
    uint8_t* o = out.ptr<uint8_t>(y);
    for (int x = 0; x < s.size.width; ++x)
      o[x] = uint8_t(std::lround(255.0f * (1.0f - smoothstep(reach, 1.5f * reach, d[x]))));
  }
  return out;
}

// The shaded luminance smoothed over the plant's pixels only (normalised convolution at a
// quarter of the resolution, where it is kept: Shared::soft_at), at twice the wash blur: what a
// wash's gradation follows.
cv::Mat smoothed_luminance(const Shared& s, const cv::Mat& covered) {
  const cv::Size small((s.size.width + 3) / 4, (s.size.height + 3) / 4);
  cv::Mat cover, lum, c_small, l_small;
  covered.convertTo(cover, CV_32F, 1.0 / 255.0);
  lum = s.luminance.mul(cover);
  cv::resize(cover, c_small, small, 0, 0, cv::INTER_AREA);
  cv::resize(lum, l_small, small, 0, 0, cv::INTER_AREA);
  const float sigma = std::max(2.0f * s.sigma, 3.0f) / 4.0f;
  cv::Mat ratio;
  cv::divide(blur(l_small, sigma), cv::max(blur(c_small, sigma), 1e-4), ratio);
  return ratio;
}

// Where the id buffer shows the wood cluster at least kSeenWoodWidth px wide at 1024 px (an
// opening: the trunk and branches a painter paints, not the thin twigs that come and go as the
// view turns), a little softened (CV_8UC1, 255 = wood). The opening's disc is that width at
// every size, so a 2048 px picture paints the branches a 1024 px one does, not the dotted
// pieces of twigs just wider than a rounded-down disc.
cv::Mat seen_wood(const cv::Mat& id, uint32_t wood_cluster, double scale) {
  cv::Mat mask = id == int32_t(wood_cluster), seen;
  const int k = std::max(3, int(std::lround(kSeenWoodWidth * scale)));
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
  const double least = kLeastWoodArea * scale * scale;
  mask.setTo(0,
             pieces_where(mask, [least](const int* st) { return st[cv::CC_STAT_AREA] < least; }));
  cv::GaussianBlur(mask, seen, cv::Size(0, 0), 0.7, 0.7, cv::BORDER_REPLICATE);
  return seen;
}

cv::Mat foliage_cover(const SurfaceSamples& samples, const Camera& camera, cv::Size size, int f,
                      float sigma, uint32_t wood) {
  const cv::Size small((size.width + f - 1) / f, (size.height + f - 1) / f);
  return crown_coverage(samples, camera, small, sigma / float(f), wood);
}

}  // namespace sylva::watercolor_internal
