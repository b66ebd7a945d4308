#include "tests/passes/edge_scenes.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <utility>

namespace sylva::test {

namespace {

struct Hit {
  float t = 0.0f;
  glm::vec3 n{0.0f};
  int id = 0;
};

bool hit_cube(const glm::vec3& o, const glm::vec3& d, Hit& hit) {
  float t_min = -1e30f, t_max = 1e30f;
  int axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12f) {
      if (o[a] < -1.0f || o[a] > 1.0f) return false;
      continue;
    }
    float t1 = (-1.0f - o[a]) / d[a], t2 = (1.0f - o[a]) / d[a];
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > t_min) {
      t_min = t1;
      axis = a;
    }
    t_max = std::min(t_max, t2);
    if (t_min > t_max) return false;
  }
  if (axis < 0 || t_min <= 0.0f) return false;
  hit.t = t_min;
  hit.n = glm::vec3(0.0f);
  hit.n[axis] = d[axis] > 0.0f ? -1.0f : 1.0f;
  hit.id = 1 + 2 * axis + (hit.n[axis] > 0.0f ? 1 : 0);
  return true;
}

bool hit_sphere(const glm::vec3& o, const glm::vec3& d, const glm::vec3& c, float r, Hit& hit) {
  const glm::vec3 oc = o - c;
  const float a = glm::dot(d, d), b = glm::dot(oc, d), k = glm::dot(oc, oc) - r * r;
  const float disc = b * b - a * k;
  if (disc < 0.0f) return false;
  const float t = (-b - std::sqrt(disc)) / a;
  if (t <= 0.0f) return false;
  hit.t = t;
  hit.n = glm::normalize(o + t * d - c);
  hit.id = 7;
  return true;
}

}  // namespace

EdgeImages render(const CubeScene& scene, int size) {
  const glm::vec3 eye = glm::vec3(1.0f) * (6.0f / std::sqrt(3.0f));
  const glm::vec3 f = glm::normalize(-eye);
  const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 u = glm::cross(r, f);
  const float focal = 0.5f * float(size) / std::tan(kHalfFov);
  auto cast = [&](float px, float py, Hit& best) {
    const glm::vec3 d = r * ((px - 0.5f * size) / focal) + u * (-(py - 0.5f * size) / focal) + f;
    bool any = false;
    Hit h;
    if (hit_cube(eye, d, h)) {
      best = h;
      any = true;
    }
    if (scene.sphere && hit_sphere(eye, d, scene.sphere_centre, scene.sphere_radius, h) &&
        (!any || h.t < best.t)) {
      best = h;
      best.n *= scene.ka;
      any = true;
    }
    return any;  // best.t is the view depth: d has unit length along f
  };
  EdgeImages im;
  im.depth = cv::Mat::zeros(size, size, CV_32FC1);
  im.normal = cv::Mat::zeros(size, size, CV_32FC3);
  im.id = cv::Mat::zeros(size, size, CV_32SC1);
  im.color = cv::Mat::zeros(size, size, CV_8UC4);
  const glm::vec3 light = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Hit h;
      if (cast(x + 0.5f, y + 0.5f, h)) {
        im.depth.at<float>(y, x) = h.t;
        im.normal.at<cv::Vec3f>(y, x) =
            cv::Vec3f(glm::dot(h.n, r), glm::dot(h.n, u), -glm::dot(h.n, f));
        im.id.at<int>(y, x) = h.id;
      }
      int covered = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          Hit s;
          covered += cast(x + (sx + 0.5f) / 4.0f, y + (sy + 0.5f) / 4.0f, s) ? 1 : 0;
        }
      const float shade = 0.25f + 0.7f * std::max(0.0f, glm::dot(glm::normalize(h.n), light));
      const uint8_t g = uint8_t(std::lround(255.0f * shade));
      im.color.at<cv::Vec4b>(y, x) =
          cv::Vec4b(g, g, g, uint8_t(std::lround(255.0f * covered / 16.0f)));
    }
  return im;
}

EdgeImages render_plane(int size, float distance, float tilt_deg, bool ortho) {
  const float a = tilt_deg * kPi / 180.0f;
  const glm::vec3 n(0.0f, std::sin(a), std::cos(a));
  const float focal = 0.5f * float(size) / std::tan(kHalfFov);
  EdgeImages im;
  im.depth.create(size, size, CV_32FC1);
  im.normal = cv::Mat(size, size, CV_32FC3, cv::Scalar(n.x, n.y, n.z));
  im.id = cv::Mat(size, size, CV_32SC1, cv::Scalar(3));
  im.color = cv::Mat(size, size, CV_8UC4, cv::Scalar(128, 128, 128, 255));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const float v = -(y + 0.5f - 0.5f * size) / focal;
      float depth;
      if (ortho) {
        // Ray from (., v * distance, 0) along -z; the view height covers the same extent.
        depth = distance - v * distance * std::tan(a);
      } else {
        const glm::vec3 d(0.0f, v, -1.0f);
        depth = (-distance * n.z) / glm::dot(n, d);
      }
      im.depth.at<float>(y, x) = depth;
    }
  return im;
}

EdgeParams all_kinds() {
  EdgeParams p;
  p.silhouette = p.depth = p.crease = p.normal = p.id = true;
  return p;
}

EdgeParams only(bool EdgeParams::*kind) {
  EdgeParams p;
  p.silhouette = p.depth = p.crease = p.normal = p.id = false;
  p.*kind = true;
  return p;
}

int count(const EdgeMarks& marks) {
  return marks.count();
}

bool same_marks(const EdgeMarks& a, const EdgeMarks& b) {
  return cv::countNonZero(a.at != b.at) == 0 && cv::countNonZero(a.between_x != b.between_x) == 0 &&
         cv::countNonZero(a.between_y != b.between_y) == 0;
}

std::vector<cv::Point2d> positions(const EdgeMarks& m) {
  std::vector<cv::Point2d> out;
  for (int y = 0; y < m.at.rows; ++y)
    for (int x = 0; x < m.at.cols; ++x) {
      if (m.at.at<uint8_t>(y, x)) out.emplace_back(x, y);
      if (x < m.between_x.cols && m.between_x.at<uint8_t>(y, x)) out.emplace_back(x + 0.5, y);
      if (y < m.between_y.rows && m.between_y.at<uint8_t>(y, x)) out.emplace_back(x, y + 0.5);
    }
  return out;
}

double farthest(const std::vector<cv::Point2d>& a, const std::vector<cv::Point2d>& b) {
  double worst = 0.0;
  for (const cv::Point2d& p : a) {
    double best = 1e30;
    for (const cv::Point2d& q : b)
      best = std::min(best, cv::norm(p - q));
    worst = std::max(worst, best);
  }
  return worst;
}

bool in_unit_range(const cv::Mat& lines) {
  if (lines.type() != CV_32FC1 || !cv::checkRange(lines)) return false;
  double lo = 0, hi = 0;
  cv::minMaxLoc(lines, &lo, &hi);
  return lo >= 0.0 && hi <= 1.0;
}

}  // namespace sylva::test
