#include "tests/passes/watercolor_scenes.h"

#include <algorithm>
#include <cmath>

namespace sylva::test {

float srgb_encode(float l) {
  l = std::clamp(l, 0.0f, 1.0f);
  return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

WatercolorScene empty_scene(cv::Size size) {
  WatercolorScene s;
  s.img.color = cv::Mat(size, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  s.img.albedo = cv::Mat(size, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  s.img.id = cv::Mat(size, CV_32SC1, cv::Scalar(0));
  s.img.depth = cv::Mat(size, CV_32FC1, cv::Scalar(0));
  s.img.position = cv::Mat(size, CV_32FC3, cv::Scalar(0, 0, 0));
  s.focal = float(size.width);
  return s;
}

void set_pixel(WatercolorScene& s, int x, int y, int32_t id, cv::Vec3f bgr_linear, float depth) {
  const cv::Size size = s.img.id.size();
  s.img.id.at<int32_t>(y, x) = id;
  s.img.depth.at<float>(y, x) = depth;
  const float u = (float(x) + 0.5f - 0.5f * float(size.width)) / s.focal;
  const float v = (float(y) + 0.5f - 0.5f * float(size.height)) / s.focal;
  s.img.position.at<cv::Vec3f>(y, x) = cv::Vec3f(u * depth, -v * depth, -depth);
  cv::Vec4b c;
  for (int ch = 0; ch < 3; ++ch)
    c[ch] = uchar(std::lround(srgb_encode(bgr_linear[ch]) * 255.0f));
  c[3] = 255;
  s.img.color.at<cv::Vec4b>(y, x) = c;
  s.img.albedo.at<cv::Vec4b>(y, x) = c;
}

// A disc of one id, its depth bulging towards the viewer like a sphere of leaves.
void add_disc(WatercolorScene& s, cv::Point2f centre, float radius, int32_t id, cv::Vec3f bgr,
              float depth) {
  const cv::Size size = s.img.id.size();
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const float dx = float(x) + 0.5f - centre.x, dy = float(y) + 0.5f - centre.y;
      const float r2 = (dx * dx + dy * dy) / (radius * radius);
      if (r2 > 1.0f) continue;
      const float z = depth - 0.1f * depth * std::sqrt(1.0f - r2);
      const float cur = s.img.depth.at<float>(y, x);
      if (cur > 0.0f && cur <= z) continue;
      set_pixel(s, x, y, id, bgr, z);
    }
}

// A clump of small leaves (ellipses) around a centre: per-leaf shading and depth jitter, so
// the clusters have the detail a real render has.
void add_clump(WatercolorScene& s, cv::RNG& rng, cv::Point2f centre, float radius, int32_t id,
               cv::Vec3f bgr, float depth, int leaves, float leaf_size) {
  const cv::Size size = s.img.id.size();
  for (int i = 0; i < leaves; ++i) {
    const float a = rng.uniform(0.0f, 6.2831853f);
    const float r = radius * std::sqrt(rng.uniform(0.0f, 1.0f));
    const cv::Point2f c(centre.x + r * std::cos(a), centre.y + r * std::sin(a));
    const float len = leaf_size * rng.uniform(0.7f, 1.3f), wid = len * 0.45f;
    const float ang = rng.uniform(0.0f, 3.14159265f);
    const float ca = std::cos(ang), sa = std::sin(ang);
    // Outer leaves nearer and brighter (what the Luft illumination does to a clump).
    const float rr = r / radius;
    const float z = depth - 0.15f * depth * std::sqrt(std::max(0.0f, 1.0f - rr * rr)) +
                    rng.uniform(-0.01f, 0.01f) * depth;
    const float shade = rng.uniform(0.6f, 1.25f) * (0.75f + 0.35f * (1.0f - rr));
    const int x0 = std::max(0, int(c.x - len)), x1 = std::min(size.width - 1, int(c.x + len));
    const int y0 = std::max(0, int(c.y - len)), y1 = std::min(size.height - 1, int(c.y + len));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const float dx = float(x) + 0.5f - c.x, dy = float(y) + 0.5f - c.y;
        const float u = (dx * ca + dy * sa) / len, v = (-dx * sa + dy * ca) / wid;
        if (u * u + v * v > 1.0f) continue;
        const float cur = s.img.depth.at<float>(y, x);
        if (cur > 0.0f && cur <= z) continue;
        // The leaf's midrib a little darker.
        const float rib = std::abs(v) < 0.15f ? 0.85f : 1.0f;
        set_pixel(s, x, y, id, bgr * (shade * rib), z);
      }
  }
}

void add_rect(WatercolorScene& s, cv::Rect r, int32_t id, cv::Vec3f bgr, float depth) {
  r &= cv::Rect(cv::Point(0, 0), s.img.id.size());
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      const float cur = s.img.depth.at<float>(y, x);
      if (cur > 0.0f && cur <= depth) continue;
      set_pixel(s, x, y, id, bgr, depth);
    }
}

WatercolorScene synthetic_tree(cv::Size size, int clusters, int leaves_per_cluster, uint64_t seed) {
  WatercolorScene s = empty_scene(size);
  cv::RNG rng(seed);
  const float w = float(size.width), h = float(size.height);
  // Trunk and two limbs (one shared non-foliage id).
  const cv::Vec3f bark(0.05f, 0.08f, 0.12f);
  add_rect(s, cv::Rect(int(0.47f * w), int(0.55f * h), int(0.06f * w), int(0.45f * h)), 1000, bark,
           6.0f);
  add_rect(s, cv::Rect(int(0.36f * w), int(0.52f * h), int(0.12f * w), int(0.018f * h)), 1000, bark,
           6.1f);
  add_rect(s, cv::Rect(int(0.52f * w), int(0.47f * h), int(0.14f * w), int(0.018f * h)), 1000, bark,
           5.9f);
  for (int c = 0; c < clusters; ++c) {
    const float a = rng.uniform(0.0f, 6.2831853f);
    const float r = std::sqrt(rng.uniform(0.0f, 1.0f));
    const cv::Point2f centre(0.5f * w + 0.33f * w * r * std::cos(a),
                             0.42f * h + 0.3f * h * r * std::sin(a));
    const float radius = w * rng.uniform(0.05f, 0.09f);
    const float depth = rng.uniform(4.0f, 8.0f);
    // Nearer clusters lighter and warmer, as the Luft illumination makes them.
    const float light = 0.6f + 0.5f * (8.0f - depth) / 4.0f;
    const cv::Vec3f green(rng.uniform(0.02f, 0.06f) * light, rng.uniform(0.16f, 0.3f) * light,
                          rng.uniform(0.05f, 0.14f) * light);
    add_clump(s, rng, centre, radius, c + 1, green, depth, leaves_per_cluster,
              w * rng.uniform(0.012f, 0.02f));
  }
  return s;
}

}  // namespace sylva::test
