#include "passes/crown_coverage.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/error.h"

namespace sylva {

namespace {

// Adds `w` at continuous image position (x, y) (pixel (i, j) centred at (i + 0.5, j + 0.5)),
// spread over the four pixels around it.
void splat(cv::Mat& d, float x, float y, float w) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  for (int dy = 0; dy < 2; ++dy) {
    const int yy = y0 + dy;
    if (yy < 0 || yy >= d.rows) continue;
    float* row = d.ptr<float>(yy);
    const float wy = dy ? ay : 1.0f - ay;
    for (int dx = 0; dx < 2; ++dx) {
      const int xx = x0 + dx;
      if (xx >= 0 && xx < d.cols) row[xx] += w * wy * (dx ? ax : 1.0f - ax);
    }
  }
}

// One sample seen by the camera: where it lands (px), the screen area it covers (px²) and its
// view depth (scene units, > 0).
struct Projected {
  float x = 0, y = 0, area = 0, depth = 0;
};

class Projector {
 public:
  explicit Projector(const Camera& camera)
      : m_camera(camera),
        m_rotation(camera.view),
        m_px_per_unit(camera.proj[1][1] * 0.5f * float(camera.height)) {}

  // Where the world point `w` lands on screen (px); (0, 0) behind the eye.
  cv::Point2f place(const glm::vec3& w) const {
    const glm::vec4 clip = m_camera.proj * (m_camera.view * glm::vec4(w, 1.0f));
    if (!(clip.w > 0.0f)) return {0.0f, 0.0f};
    return {(clip.x / clip.w * 0.5f + 0.5f) * float(m_camera.width),
            (0.5f - clip.y / clip.w * 0.5f) * float(m_camera.height)};
  }

  // False for a sample behind the eye or of no area on screen.
  bool project(const SurfaceSamples& s, size_t i, Projected& p) const {
    const glm::vec4 v = m_camera.view * glm::vec4(s.positions[i], 1.0f);
    const glm::vec4 clip = m_camera.proj * v;
    if (!(clip.w > 0.0f) || (!m_camera.ortho && v.z >= 0.0f)) return false;
    const glm::vec3 n = m_rotation * s.normals[i];
    const glm::vec3 to_eye = m_camera.ortho ? glm::vec3(0, 0, 1) : glm::normalize(-glm::vec3(v));
    // px per scene unit: at depth 1 in perspective (then divided by the depth), everywhere in
    // orthographic projection.
    const float scale = m_camera.ortho ? m_px_per_unit : m_px_per_unit / -v.z;
    p.area = s.areas[i] * std::abs(glm::dot(n, to_eye)) * scale * scale;
    p.x = (clip.x / clip.w * 0.5f + 0.5f) * float(m_camera.width);
    p.y = (0.5f - clip.y / clip.w * 0.5f) * float(m_camera.height);
    p.depth = -v.z;
    return std::isfinite(p.area) && std::isfinite(p.x) && std::isfinite(p.y) && p.area > 0.0f;
  }

 private:
  const Camera& m_camera;
  glm::mat3 m_rotation;
  float m_px_per_unit;
};

// A part: its cluster, mean view depth, projected centre and projected samples.
struct Part {
  uint32_t cluster = 0;
  float depth = 0;
  glm::vec3 centre{0.0f};  // world space
  std::vector<Projected> points;
};

// The parts of the samples' clusters (but 0, and `wood` unless `wood_behind`) as the camera sees
// them, nearest last; the wood first with `wood_behind`.
// With `by_instance` the parts are the instances (their index + 1), of their foliage only.
std::vector<Part> parts_back_to_front(const SurfaceSamples& s, const Projector& projector,
                                      uint32_t wood, bool wood_behind, bool by_instance = false) {
  const uint32_t skip = wood_behind ? 0 : wood;
  std::map<uint32_t, Part> by_cluster;
  std::map<uint32_t, double> area, weighted;
  std::map<uint32_t, glm::dvec3> centre;
  Projected p;
  for (size_t i = 0; i < s.size(); ++i) {
    if (by_instance && (s.clusters[i] == 0 || s.clusters[i] == wood)) continue;
    const uint32_t c = by_instance ? s.instances[i] : s.clusters[i];
    if (c == 0 || c == skip || !projector.project(s, i, p)) continue;
    Part& part = by_cluster[c];
    part.cluster = c;
    part.points.push_back(p);
    area[c] += p.area;
    weighted[c] += double(p.area) * p.depth;
    centre[c] += double(p.area) * glm::dvec3(s.positions[i]);
  }
  std::vector<Part> out;
  for (auto& [c, part] : by_cluster) {
    part.depth = float(weighted[c] / area[c]);
    part.centre = glm::vec3(centre[c] / area[c]);
    out.push_back(std::move(part));
  }
  std::stable_sort(out.begin(), out.end(), [wood](const Part& a, const Part& b) {
    if ((a.cluster == wood) != (b.cluster == wood)) return a.cluster == wood;
    return a.depth > b.depth;
  });
  return out;
}

// The box of the image a part's smoothed density can reach.
cv::Rect part_box(const Part& part, double sigma, cv::Size size) {
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (const Projected& p : part.points) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  const int pad = int(std::ceil(3.0 * sigma)) + 2;
  return cv::Rect(cv::Point(int(std::floor(x0)) - pad, int(std::floor(y0)) - pad),
                  cv::Point(int(std::ceil(x1)) + pad, int(std::ceil(y1)) + pad)) &
         cv::Rect(0, 0, size.width, size.height);
}

// Where `part`'s smoothed coverage reaches `level`, in its box of an image of `size`.
PartMask part_mask(const Part& part, const Projector& projector, double sigma, float level,
                   cv::Size size) {
  PartMask m;
  m.cluster = part.cluster;
  m.depth = part.depth;
  m.centre = projector.place(part.centre);
  m.box = part_box(part, sigma, size);
  if (m.box.empty()) return m;
  cv::Mat density(m.box.size(), CV_32FC1, cv::Scalar(0));
  for (const Projected& p : part.points)
    splat(density, p.x - float(m.box.x), p.y - float(m.box.y), p.area);
  cv::GaussianBlur(density, density, {0, 0}, sigma, 0, cv::BORDER_CONSTANT);
  const float enough = -std::log(1.0f - level);  // the density whose coverage is `level`
  m.mask = density >= enough;
  return m;
}

}  // namespace

cv::Mat project_surface_density(const SurfaceSamples& samples, const Camera& camera,
                                uint32_t skip) {
  SYLVA_CHECK(camera.width > 0 && camera.height > 0, "project_surface_density: an empty frame");
  cv::Mat d(camera.height, camera.width, CV_32FC1, cv::Scalar(0));
  const Projector projector(camera);
  Projected p;
  for (size_t i = 0; i < samples.size(); ++i)
    if ((skip == 0 || samples.clusters[i] != skip) && projector.project(samples, i, p))
      splat(d, p.x, p.y, p.area);
  return d;
}

cv::Mat crown_coverage(const SurfaceSamples& samples, const Camera& camera, cv::Size size,
                       double sigma, uint32_t skip) {
  Camera sized = camera;
  sized.width = size.width;
  sized.height = size.height;
  cv::Mat d = project_surface_density(samples, sized, skip);
  if (sigma > 0.0) cv::GaussianBlur(d, d, {0, 0}, sigma);
  cv::exp(-d, d);
  return 1.0f - d;
}

std::vector<PartMask> project_part_masks(const SurfaceSamples& samples, const Camera& camera,
                                         double sigma, float level, uint32_t wood, float wood_level,
                                         double wood_sigma) {
  SYLVA_CHECK(camera.width > 0 && camera.height > 0, "project_part_masks: an empty frame");
  SYLVA_CHECK(
      sigma > 0.0 && level > 0.0f && level < 1.0f && wood_level >= 0.0f && wood_level < 1.0f,
      "project_part_masks: sigma > 0, levels in (0, 1)");
  const bool wood_behind = wood != 0 && wood_level > 0.0f;
  const Projector projector(camera);
  const cv::Size size(camera.width, camera.height);
  std::vector<PartMask> out;
  for (const Part& part : parts_back_to_front(samples, projector, wood, wood_behind))
    out.push_back(
        part.cluster == wood
            ? part_mask(part, projector, wood_sigma > 0.0 ? wood_sigma : sigma, wood_level, size)
            : part_mask(part, projector, sigma, level, size));
  return out;
}

CrownParts project_crown_parts(const SurfaceSamples& samples, const Camera& camera, double sigma,
                               float level, uint32_t wood, float wood_level, double wood_sigma) {
  CrownParts parts;
  parts.label = cv::Mat(camera.height, camera.width, CV_32SC1, cv::Scalar(0));
  parts.depth = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(0));
  for (const PartMask& m :
       project_part_masks(samples, camera, sigma, level, wood, wood_level, wood_sigma)) {
    parts.order.push_back({m.cluster, m.depth, m.centre});
    if (m.box.empty()) continue;
    parts.label(m.box).setTo(int(m.cluster), m.mask);
    parts.depth(m.box).setTo(m.depth, m.mask);
  }
  return parts;
}

CrownParts project_plant_parts(const SurfaceSamples& samples, const Camera& camera, double sigma,
                               float level, uint32_t wood) {
  SYLVA_CHECK(camera.width > 0 && camera.height > 0, "project_plant_parts: an empty frame");
  SYLVA_CHECK(sigma > 0.0 && level > 0.0f && level < 1.0f,
              "project_plant_parts: sigma > 0, level in (0, 1)");
  CrownParts parts;
  parts.label = cv::Mat(camera.height, camera.width, CV_32SC1, cv::Scalar(0));
  parts.depth = cv::Mat(camera.height, camera.width, CV_32FC1, cv::Scalar(0));
  if (samples.instances.size() != samples.size()) return parts;
  const Projector projector(camera);
  const cv::Size size(camera.width, camera.height);
  for (const Part& part : parts_back_to_front(samples, projector, wood, false, true)) {
    const PartMask m = part_mask(part, projector, sigma, level, size);
    parts.order.push_back({m.cluster, m.depth, m.centre});
    if (m.box.empty()) continue;
    parts.label(m.box).setTo(int(m.cluster), m.mask);
    parts.depth(m.box).setTo(m.depth, m.mask);
  }
  return parts;
}

}  // namespace sylva
