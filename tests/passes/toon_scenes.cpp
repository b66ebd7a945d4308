// The synthetic G-buffers of the toon tests (tests/passes/toon_scenes.h).
#include "tests/passes/toon_scenes.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sylva::test {

float decode(uint8_t v) {
  const float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t encode(float lin) {
  lin = std::clamp(lin, 0.0f, 1.0f);
  const float c = lin <= 0.0031308f ? lin * 12.92f : 1.055f * std::pow(lin, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(c * 255.0f));
}

// One directional light along view +Z (toward the viewer), camera-fixed.
Lighting headlight() {
  Lighting l;
  Light key;
  key.vector = glm::vec3(0.0f, 0.0f, 1.0f);
  key.color = glm::vec3(1.0f);
  l.lights = {key};
  return l;
}

// Normals sweeping from facing away from +Z (x = 0) to facing it (x = width - 1):
// N·L = cos(theta), theta = pi (1 - (x + 0.5) / width), so N·L rises monotonically.
ToonImages ramp(int width, int height, float ka) {
  ToonImages in;
  in.normal.create(height, width, CV_32FC3);
  for (int x = 0; x < width; ++x) {
    const float theta = kPi * (1.0f - (float(x) + 0.5f) / float(width));
    for (int y = 0; y < height; ++y)
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(std::sin(theta), 0.0f, std::cos(theta));
  }
  in.albedo = cv::Mat(height, width, CV_8UC4, kAlbedo);
  in.ka = cv::Mat(height, width, CV_32FC1, cv::Scalar(ka));
  return in;
}

// First pixel where N·L = cos(theta(x)) >= t on the ramp.
int ramp_crossing(float t, int width) {
  return int(std::ceil(float(width) * (1.0f - std::acos(t) / kPi) - 0.5f));
}

std::vector<BandRun> runs(const cv::Mat& img, int row) {
  std::vector<BandRun> r;
  for (int x = 0; x < img.cols; ++x) {
    const cv::Vec4b c = img.at<cv::Vec4b>(row, x);
    if (r.empty() || r.back().color != c) r.push_back({x, c});
  }
  return r;
}

// A unit sphere seen head-on, with analytic normals, 4x4-sample coverage (colour
// premultiplied by coverage in linear light, as the raster pass leaves it), view-space
// positions at distance 5 and a ka darkening toward the bottom, as under a crown.
ToonImages sphere(int size, cv::Vec4b albedo) {
  ToonImages in;
  in.normal = cv::Mat(size, size, CV_32FC3, cv::Scalar::all(0));
  in.albedo = cv::Mat(size, size, CV_8UC4, cv::Scalar::all(0));
  in.ka = cv::Mat(size, size, CV_32FC1, cv::Scalar(0));
  in.position = cv::Mat(size, size, CV_32FC3, cv::Scalar::all(0));
  const float r = 0.45f * float(size), c = 0.5f * float(size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      int covered = 0;
      glm::vec3 nsum(0.0f);
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const float u = (float(x) + (float(sx) + 0.5f) / 4.0f - c) / r;
          const float v = -(float(y) + (float(sy) + 0.5f) / 4.0f - c) / r;
          if (u * u + v * v >= 1.0f) continue;
          ++covered;
          nsum += glm::vec3(u, v, std::sqrt(1.0f - u * u - v * v));
        }
      if (covered == 0) continue;
      const glm::vec3 n = glm::normalize(nsum);
      const float cov = float(covered) / 16.0f;
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(n.x, n.y, n.z);
      in.position.at<cv::Vec3f>(y, x) = cv::Vec3f(n.x, n.y, n.z - 5.0f);
      in.ka.at<float>(y, x) = 0.45f + 0.275f * (1.0f + n.y);
      cv::Vec4b a;
      for (int ch = 0; ch < 3; ++ch)
        a[ch] = encode(decode(albedo[ch]) * cov);
      a[3] = uint8_t(std::lround(cov * 255.0f));
      in.albedo.at<cv::Vec4b>(y, x) = a;
    }
  return in;
}

// Shadow map of a plane at light depth 10 seen by an orthographic light camera at z = 10
// looking down -Z over [-1, 1]^2, with a square occluder at depth 5 over texels 8..23.
ToonShadowMap square_shadow_map(bool occluder) {
  ToonShadowMap m;
  m.depth = cv::Mat(32, 32, CV_32FC1, cv::Scalar(10.0f));
  if (occluder) m.depth(cv::Rect(8, 8, 16, 16)).setTo(5.0f);
  m.light_view = glm::lookAt(glm::vec3(0, 0, 10), glm::vec3(0), glm::vec3(0, 1, 0));
  m.light_proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 100.0f);
  return m;
}

// The view-space plane z = -slope x over [-1, 1]^2 (64 x 64 px), facing +Z, with the
// identity view so world = view space.
ToonImages plane(float slope) {
  ToonImages in;
  const int n = 64;
  in.normal.create(n, n, CV_32FC3);
  in.position.create(n, n, CV_32FC3);
  const glm::vec3 normal = glm::normalize(glm::vec3(slope, 0.0f, 1.0f));
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const float px = (float(x) + 0.5f) / float(n) * 2.0f - 1.0f;
      const float py = 1.0f - (float(y) + 0.5f) / float(n) * 2.0f;
      in.position.at<cv::Vec3f>(y, x) = cv::Vec3f(px, py, -slope * px);
      in.normal.at<cv::Vec3f>(y, x) = cv::Vec3f(normal.x, normal.y, normal.z);
    }
  in.albedo = cv::Mat(n, n, CV_8UC4, kAlbedo);
  return in;
}

bool all_finite(const cv::Mat& m) {
  return cv::checkRange(m);
}

}  // namespace sylva::test
