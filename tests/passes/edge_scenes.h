// Analytic G-buffers for the edges tests (tests/passes/test_edges*.cpp), built by ray casting
// (no GL): a cube seen corner-on, optionally with a sphere in front of it, and a tilted plane;
// plus the helpers the tests compare marks with.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "passes/edges.h"

namespace sylva::test {

inline constexpr float kPi = 3.14159265358979f;
inline constexpr float kHalfFov = 20.0f * kPi / 180.0f;  // 40 degree vertical field of view

// The cube [-1, 1]^3 seen from (1, 1, 1) * 6 / sqrt(3) (so its corner (1, 1, 1) is at the image
// centre), optionally with a sphere in front of its right side (depth jumps, smooth normals).
// Ids: cube faces 1 + 2 axis + (outward along +axis), sphere 7, background 0.
struct CubeScene {
  bool sphere = false;
  glm::vec3 sphere_centre{2.0f, 1.2f, 0.6f};
  float sphere_radius = 0.6f;
  float ka = 1.0f;  // the sphere's normals have this length (realigned-scaled, Luft Fig. 7c)
};

// G-buffers of the scene at size x size: depth, normal and id from the pixel-centre ray,
// colour alpha from 4 x 4 samples (coverage), colour a grey Lambert shade.
EdgeImages render(const CubeScene& scene, int size);

// A plane filling the view: view-space point (0, 0, -distance), normal tilted `tilt_deg` from
// the view axis about the x axis. Perspective as above, or orthographic (depth linear).
EdgeImages render_plane(int size, float distance, float tilt_deg, bool ortho = false);

// Every kind of line enabled; or only `kind`.
EdgeParams all_kinds();
EdgeParams only(bool EdgeParams::*kind);

int count(const EdgeMarks& marks);

// 4-neighbour pairs (right and down) as (y, x, y2, x2).
template <class Visit>
void for_pairs(const cv::Size& s, Visit visit) {
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      if (x + 1 < s.width) visit(y, x, y, x + 1);
      if (y + 1 < s.height) visit(y, x, y + 1, x);
    }
}

// The marks expected exactly between the 4-neighbours for which differ(y, x, y2, x2) holds.
template <class Differ>
EdgeMarks pair_marks(const cv::Size& s, Differ differ) {
  EdgeMarks m;
  m.at = cv::Mat::zeros(s, CV_8UC1);
  m.between_x = cv::Mat::zeros(s.height, s.width - 1, CV_8UC1);
  m.between_y = cv::Mat::zeros(s.height - 1, s.width, CV_8UC1);
  for_pairs(s, [&](int y, int x, int y2, int x2) {
    if (differ(y, x, y2, x2)) (y2 == y ? m.between_x : m.between_y).at<uint8_t>(y, x) = 255;
  });
  return m;
}

bool same_marks(const EdgeMarks& a, const EdgeMarks& b);

// Mark positions in pixel coordinates (pixel centres at integers).
std::vector<cv::Point2d> positions(const EdgeMarks& m);

// Largest distance from a point of `a` to its nearest point of `b` (brute force).
double farthest(const std::vector<cv::Point2d>& a, const std::vector<cv::Point2d>& b);

// CV_32FC1, finite, in [0, 1].
bool in_unit_range(const cv::Mat& lines);

}  // namespace sylva::test
