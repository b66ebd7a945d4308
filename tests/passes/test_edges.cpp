// Edges: property tests on G-buffers built analytically here by ray casting (no GL): a tilted
// plane has no interior edge at any distance; a cube seen corner-on gives its silhouette from
// coverage and its three creases from normals and from second-order depth; counts fall as
// thresholds rise; the width scales with the resolution; id boundaries are exact; the vector
// metric on short (low-ka) normals gives fewer lines; extremes and determinism; and the graph
// reads only what the enabled kinds need. With SYLVA_EDGES_LOOK_DIR set, also writes the cube's
// lines as PNGs for a visual check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <glm/glm.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "passes/composite.h"
#include "passes/edges.h"

namespace sylva::test {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kHalfFov = 20.0f * kPi / 180.0f;  // 40 degree vertical field of view

// ---- Analytic scenes ------------------------------------------------------------------------

// The cube [-1, 1]^3 seen from (1, 1, 1) * 6 / sqrt(3) (so its corner (1, 1, 1) is at the image
// centre), optionally with a sphere in front of its right side (depth jumps, smooth normals).
// Ids: cube faces 1 + 2 axis + (outward along +axis), sphere 7, background 0.
struct CubeScene {
  bool sphere = false;
  glm::vec3 sphere_centre{2.0f, 1.2f, 0.6f};
  float sphere_radius = 0.6f;
  float ka = 1.0f;  // the sphere's normals have this length (realigned-scaled, Luft Fig. 7c)
};

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

// G-buffers of the scene at size x size: depth, normal and id from the pixel-centre ray,
// colour alpha from 4 x 4 samples (coverage), colour a grey Lambert shade.
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

// A plane filling the view: view-space point (0, 0, -distance), normal tilted `tilt_deg` from
// the view axis about the x axis. Perspective as above, or orthographic (depth linear).
EdgeImages render_plane(int size, float distance, float tilt_deg, bool ortho = false) {
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

bool same_marks(const EdgeMarks& a, const EdgeMarks& b) {
  return cv::countNonZero(a.at != b.at) == 0 && cv::countNonZero(a.between_x != b.between_x) == 0 &&
         cv::countNonZero(a.between_y != b.between_y) == 0;
}

// Mark positions in pixel coordinates (pixel centres at integers).
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

// Largest distance from a point of `a` to its nearest point of `b` (brute force).
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

// ---- Tests -------------------------------------------------------------------------------------

TEST(Edges, TiltedPlaneHasNoInteriorEdgeAtAnyDistance) {
  // Up to 60 degrees: at the top of the view the plane is then seen at 30 degrees from grazing.
  for (float tilt : {0.0f, 30.0f, 60.0f})
    for (float distance : {2.0f, 200.0f}) {
      const EdgeImages in = render_plane(256, distance, tilt);
      EXPECT_EQ(count(mark_edges(in, all_kinds())), 0) << "tilt " << tilt << " at " << distance;
    }
  // Orthographic: depth linear on screen; the crease test is exact there too.
  EXPECT_EQ(count(mark_edges(render_plane(256, 5.0f, 60.0f, true), all_kinds())), 0);
}

TEST(Edges, RelativeDepthDoesNotDependOnDistance) {
  // The same scene scaled: relative depth differences are unchanged, so are the marks.
  EdgeImages near_scene = render(CubeScene{.sphere = true}, 256);
  EdgeImages far_scene = near_scene;
  far_scene.depth = near_scene.depth * 40.0;
  const EdgeParams p = all_kinds();
  EXPECT_TRUE(same_marks(mark_edges(near_scene, p), mark_edges(far_scene, p)));
}

TEST(Edges, CubeSilhouetteComesFromCoverage) {
  const int size = 256;
  EdgeImages in = render(CubeScene{}, size);
  auto fg = [&](int y, int x) { return in.depth.at<float>(y, x) > 0.0f; };
  // Coverage from depth (no colour given): exactly between covered and uncovered pixels.
  EdgeImages depth_only;
  depth_only.depth = in.depth;
  const EdgeMarks m = mark_edges(depth_only, only(&EdgeParams::silhouette));
  EXPECT_GT(count(m), 4 * size / 2);  // a hexagon about half the image across
  EXPECT_TRUE(same_marks(m, pair_marks(in.depth.size(), [&](int y, int x, int y2, int x2) {
                           return fg(y, x) != fg(y2, x2);
                         })));
  // From the colour's alpha (coverage >= 1/2 rather than any sample): the same outline
  // within a pixel.
  const EdgeMarks ma = mark_edges(in, only(&EdgeParams::silhouette));
  EXPECT_LE(farthest(positions(ma), positions(m)), 1.0);
  EXPECT_LE(farthest(positions(m), positions(ma)), 1.0);
  // The cube is convex: no depth discontinuity inside.
  EXPECT_EQ(count(mark_edges(in, only(&EdgeParams::depth))), 0);
}

// Between two different non-zero ids.
auto id_change(const cv::Mat& id) {
  return [&id](int y, int x, int y2, int x2) {
    const int a = id.at<int>(y, x), b = id.at<int>(y2, x2);
    return a != 0 && b != 0 && a != b;
  };
}

TEST(Edges, CubeCreasesFromNormals) {
  const EdgeImages in = render(CubeScene{}, 256);
  const EdgeMarks m = mark_edges(in, only(&EdgeParams::normal));
  // Flat faces: the lines are exactly between pixels of different faces.
  const EdgeMarks faces = pair_marks(in.id.size(), id_change(in.id));
  EXPECT_TRUE(same_marks(m, faces));
  // All three creases: the visible faces are +X (id 2), +Y (4), +Z (6).
  std::set<std::pair<int, int>> pairs;
  for_pairs(in.id.size(), [&](int y, int x, int y2, int x2) {
    if (id_change(in.id)(y, x, y2, x2))
      pairs.insert(std::minmax(in.id.at<int>(y, x), in.id.at<int>(y2, x2)));
  });
  EXPECT_EQ(pairs, (std::set<std::pair<int, int>>{{2, 4}, {2, 6}, {4, 6}}));
}

TEST(Edges, CubeCreasesFromSecondOrderDepth) {
  const EdgeImages in = render(CubeScene{}, 256);
  const EdgeMarks m = mark_edges(in, only(&EdgeParams::crease));
  const std::vector<cv::Point2d> found = positions(m);
  const std::vector<cv::Point2d> creases = positions(pair_marks(in.id.size(), id_change(in.id)));
  ASSERT_FALSE(found.empty());
  EXPECT_LE(farthest(found, creases), 1.5);  // every mark on a crease
  // Every crease marked (the last pixel or two before the silhouette has no covered pixel
  // beyond it for the second difference).
  EXPECT_LE(farthest(creases, found), 2.0);
  EXPECT_LT(found.size(), creases.size() * 5 / 4);  // thin: marked once across
}

TEST(Edges, CountsFallAsThresholdsRise) {
  const EdgeImages in = render(CubeScene{.sphere = true}, 256);
  struct Sweep {
    float EdgeParams::*threshold;
    std::vector<float> values;
  };
  const std::vector<Sweep> sweeps = {
      {&EdgeParams::depth_threshold, {0.001f, 0.003f, 0.01f, 0.03f, 0.1f, 0.3f, 1.0f, 10.0f}},
      {&EdgeParams::crease_threshold, {0.01f, 0.1f, 0.3f, 1.0f, 3.0f, 10.0f, 30.0f, 100.0f}},
      {&EdgeParams::normal_threshold, {0.5f, 2.0f, 5.0f, 10.0f, 20.0f, 45.0f, 90.0f, 180.0f}},
  };
  for (const Sweep& s : sweeps) {
    EdgeParams p = all_kinds();
    int previous = -1;
    double previous_sum = 0.0;
    int first = 0, last = 0;
    for (float v : s.values) {
      p.*s.threshold = v;
      const int c = count(mark_edges(in, p));
      const double sum = cv::sum(detect_edges(in, p))[0];
      if (previous >= 0) {
        EXPECT_LE(c, previous) << "at " << v;
        EXPECT_LE(sum, previous_sum + 1e-3) << "at " << v;
      } else {
        first = c;
      }
      previous = c;
      previous_sum = sum;
      last = c;
    }
    EXPECT_LT(last, first);  // the sweep is not vacuous
  }
}

// Sum of line coverage across the vertical crease below the cube's centre (between faces +X
// and +Z), averaged over rows: the line's width in px.
double vertical_crease_width(const cv::Mat& lines) {
  const int s = lines.rows;
  const int half = std::max(4, int(0.05 * s));
  double total = 0.0;
  int rows = 0;
  for (int y = s / 2 + s / 16; y < s / 2 + s / 8; ++y, ++rows)
    for (int x = s / 2 - half; x < s / 2 + half; ++x)
      total += lines.at<float>(y, x);
  return total / rows;
}

TEST(Edges, WidthScalesWithResolution) {
  EdgeParams p;
  p.width = 3.0f;  // 1.5 px at 512, 6 px at 2048
  const cv::Mat small = detect_edges(render(CubeScene{}, 512), p);
  const cv::Mat big = detect_edges(render(CubeScene{}, 2048), p);
  const double w_small = vertical_crease_width(small), w_big = vertical_crease_width(big);
  EXPECT_NEAR(w_small, 1.5, 0.15);
  EXPECT_NEAR(w_big, 6.0, 0.3);
  EXPECT_NEAR(w_big / w_small, 4.0, 0.3);
  // Line area: 4x the length times 4x the width.
  const double area = cv::sum(big)[0] / cv::sum(small)[0];
  EXPECT_NEAR(area, 16.0, 1.6);
  const double pixels = double(cv::countNonZero(big >= 0.5)) / cv::countNonZero(small >= 0.5);
  EXPECT_NEAR(pixels, 16.0, 2.0);
}

TEST(Edges, LinesAreAntialiasedAndEvenInWidth) {
  // A disc's outline has every direction: its line area per unit length is the width, and
  // each 45-degree sector (axis-aligned or diagonal) holds an eighth of it.
  const int s = 256;
  const double r = 90.0, cx = 128.3, cy = 127.8;
  EdgeImages in;
  in.depth = cv::Mat::zeros(s, s, CV_32FC1);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x)
      if (std::hypot(x - cx, y - cy) < r) in.depth.at<float>(y, x) = 1.0f;
  EdgeParams p = only(&EdgeParams::silhouette);
  for (double width : {0.5, 1.0, 1.5, 3.0, 6.0}) {
    p.width = float(width * 1024.0 / s);
    const cv::Mat lines = detect_edges(in, p);
    EXPECT_NEAR(cv::sum(lines)[0] / (2.0 * kPi * r), width, 0.03 * width + 0.02) << width;
    double sector[8] = {};
    int partial = 0;
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        const float v = lines.at<float>(y, x);
        const double a = std::atan2(y - cy, x - cx) + kPi;  // [0, 2 pi]
        sector[std::min(7, int(a / (kPi / 4.0)))] += v;
        partial += (v > 0.02f && v < 0.98f) ? 1 : 0;
      }
    for (double v : sector)
      EXPECT_NEAR(v / (cv::sum(lines)[0] / 8.0), 1.0, 0.05) << width;
    EXPECT_GT(partial, int(2.0 * kPi * r));  // soft edges all round, not a binary mask
  }
}

TEST(Edges, IdBoundariesAreExactlyWhereIdsChange) {
  // Random rectangles of ids over a background, and the cube + sphere scene.
  cv::Mat ids = cv::Mat::zeros(120, 160, CV_32SC1);
  cv::RNG rng(7);
  for (int k = 0; k < 40; ++k) {
    const int x = rng.uniform(0, 150), y = rng.uniform(0, 110);
    ids(cv::Rect(x, y, rng.uniform(3, 160 - x), rng.uniform(3, 120 - y))).setTo(rng.uniform(1, 9));
  }
  for (const cv::Mat& id : {ids, render(CubeScene{.sphere = true}, 200).id}) {
    EdgeImages in;
    in.id = id;
    const EdgeMarks expected = pair_marks(id.size(), id_change(id));
    EXPECT_GT(count(expected), 0);
    EXPECT_TRUE(same_marks(mark_edges(in, only(&EdgeParams::id)), expected));
  }
}

TEST(Edges, VectorMetricOnShortNormalsGivesFewerEdges) {
  EdgeParams p = only(&EdgeParams::normal);
  p.normal_threshold = 3.0f;  // the sphere's limb turns faster than this per pixel
  // Unit normals: both metrics are the same test.
  const EdgeImages unit = render(CubeScene{.sphere = true}, 256);
  const int angle_unit = count(mark_edges(unit, p));
  p.normal_metric = "vector";
  EXPECT_EQ(count(mark_edges(unit, p)), angle_unit);
  // The sphere's normals scaled by ka = 0.3, as realigned-scaled normals deep in a crown.
  const EdgeImages scaled = render(CubeScene{.sphere = true, .ka = 0.3f}, 256);
  p.normal_metric = "angle";
  const int angle = count(mark_edges(scaled, p));
  p.normal_metric = "vector";
  const int vector = count(mark_edges(scaled, p));
  EXPECT_EQ(angle, angle_unit);  // the angle metric ignores the length
  EXPECT_LT(vector, angle);
}

TEST(Edges, DepthWidthAndFadeFollowDepth) {
  // Two fronto-parallel squares, near (depth 2) and far (depth 8): silhouettes only.
  const int s = 256;
  EdgeImages in;
  in.depth = cv::Mat::zeros(s, s, CV_32FC1);
  in.depth(cv::Rect(20, 40, 80, 160)).setTo(2.0f);
  in.depth(cv::Rect(150, 40, 80, 160)).setTo(8.0f);
  EdgeParams p = only(&EdgeParams::silhouette);
  p.width = 16.0f;  // 4 px at 256
  p.depth_width = 4.0f;
  const cv::Mat lines = detect_edges(in, p);
  auto width_at = [&](int x0, int x1) {  // across a vertical side, mid-height
    double w = 0.0;
    for (int x = x0; x < x1; ++x)
      w += lines.at<float>(120, x);
    return w;
  };
  EXPECT_NEAR(width_at(5, 35), 4.0, 0.1);     // near: full width
  EXPECT_NEAR(width_at(135, 165), 1.0, 0.1);  // far: a quarter

  p.depth_width = 1.0f;
  p.fade = 1.0f;
  const cv::Mat faded = detect_edges(in, p);
  double near_max = 0, far_max = 0;
  cv::minMaxLoc(faded(cv::Rect(0, 0, 128, s)), nullptr, &near_max);
  cv::minMaxLoc(faded(cv::Rect(128, 0, 128, s)), nullptr, &far_max);
  EXPECT_FLOAT_EQ(float(near_max), 1.0f);
  EXPECT_FLOAT_EQ(float(far_max), 0.0f);  // the farthest lines vanish
}

TEST(Edges, EveryParameterAtBothEndsGivesValidOutput) {
  const EdgeImages in = render(CubeScene{.sphere = true}, 128);
  EdgeParams defaults = all_kinds();
  defaults.depth_width = 2.0f;
  defaults.fade = 0.5f;
  EdgeParams probe = defaults;
  ParamSet set;
  bind_edge_params(set, probe);
  ASSERT_GE(set.specs().size(), 13u);
  for (const ParamSpec& spec : set.specs()) {
    std::vector<std::string> values;
    switch (spec.type) {
      case ParamType::Float:
        values = {std::to_string(spec.min_open ? spec.min + 1e-3 : spec.min),
                  std::to_string(spec.max)};
        // Just outside the range is an input error.
        EXPECT_THROW(set.set_number(spec.key, spec.max * 1.01 + 0.01, "test"), InputError);
        EXPECT_THROW(set.set_number(spec.key, spec.min - 0.01, "test"), InputError);
        break;
      case ParamType::Bool:
        values = {"false", "true"};
        break;
      case ParamType::Choice:
        values = spec.choices;
        EXPECT_THROW(set.set_text(spec.key, "nonsense", "test"), InputError);
        break;
      case ParamType::Color:
        values = {"#000000", "#ffffff"};
        break;
      default:
        ADD_FAILURE() << "unexpected parameter type for " << spec.key;
    }
    for (const std::string& v : values) {
      probe = defaults;
      set.set_from_string(spec.key, v, "test");
      const cv::Mat lines = detect_edges(in, probe);
      EXPECT_EQ(lines.size(), in.depth.size());
      EXPECT_TRUE(in_unit_range(lines)) << spec.key << " = " << v;
    }
  }
}

TEST(Edges, SameInputSameBytes) {
  const EdgeImages in = render(CubeScene{.sphere = true}, 200);
  EdgeParams p = all_kinds();
  p.depth_width = 3.0f;
  p.fade = 0.4f;
  const cv::Mat a = detect_edges(in, p), b = detect_edges(in, p);
  ASSERT_EQ(a.total() * a.elemSize(), b.total() * b.elemSize());
  EXPECT_EQ(std::memcmp(a.data, b.data, a.total() * a.elemSize()), 0);
}

TEST(Edges, EmptySceneHasNoLines) {
  EdgeImages in;
  in.depth = cv::Mat::zeros(64, 64, CV_32FC1);
  in.normal = cv::Mat::zeros(64, 64, CV_32FC3);
  in.id = cv::Mat::zeros(64, 64, CV_32SC1);
  const cv::Mat lines = detect_edges(in, all_kinds());
  EXPECT_EQ(cv::countNonZero(lines), 0);
}

// Dummy G-buffer writers; records which ran.
struct GraphFixture {
  RenderGraph g;
  EdgeResources r;
  std::string ran;
  EdgeImages images = render(CubeScene{.sphere = true}, 96);
  GraphFixture() {
    r.normal = g.resource("normal");
    r.depth = g.resource("depth");
    r.id = g.resource("id");
    r.color = g.resource("color");
    const std::pair<int, cv::Mat> writers[] = {{r.normal, images.normal},
                                               {r.depth, images.depth},
                                               {r.id, images.id},
                                               {r.color, images.color}};
    for (const auto& [res, image] : writers)
      g.add_pass("write-" + g.resource_name(res), {}, {res},
                 [this, res = res, image = image](PassContext& c) {
                   ran += g.resource_name(res) + ";";
                   c.write(res, image);
                 });
  }
};

TEST(Edges, GraphReadsOnlyWhatEnabledKindsNeed) {
  {
    GraphFixture f;
    EdgeParams p = only(&EdgeParams::normal);
    p.silhouette = true;
    EdgeResources no_color = f.r;
    no_color.color = -1;
    const int out = add_edges_pass(f.g, no_color, p);
    EXPECT_EQ(f.g.resource_name(out), "edges");
    f.g.present(out);
    f.g.compile();
    EXPECT_TRUE(f.g.pass_live("write-normal"));
    EXPECT_FALSE(f.g.pass_live("write-depth"));
    EXPECT_FALSE(f.g.pass_live("write-id"));
    EXPECT_FALSE(f.g.pass_live("write-color"));
    f.g.execute();
    EXPECT_EQ(f.ran, "normal;");
    const cv::Mat& lines = f.g.get<cv::Mat>(out);
    EdgeImages normals_only;
    normals_only.normal = f.images.normal;
    EXPECT_EQ(cv::countNonZero(lines != detect_edges(normals_only, p)), 0);
  }
  {
    // With the colour given, the silhouette takes its coverage; without silhouettes, it is
    // not read either.
    GraphFixture f;
    EdgeParams p = only(&EdgeParams::normal);
    p.silhouette = true;
    f.g.present(add_edges_pass(f.g, f.r, p));
    f.g.compile();
    EXPECT_TRUE(f.g.pass_live("write-color"));
    EXPECT_FALSE(f.g.pass_live("write-depth"));
    EXPECT_FALSE(f.g.pass_live("write-id"));
  }
  {
    GraphFixture f;
    f.g.present(add_edges_pass(f.g, f.r, only(&EdgeParams::normal)));
    f.g.compile();
    EXPECT_FALSE(f.g.pass_live("write-color"));
    EXPECT_FALSE(f.g.pass_live("write-id"));
  }
  {
    // Depth-dependent width reads depth even without depth edges.
    GraphFixture f;
    EdgeParams p = only(&EdgeParams::normal);
    p.fade = 0.5f;
    f.g.present(add_edges_pass(f.g, f.r, p));
    f.g.compile();
    EXPECT_TRUE(f.g.pass_live("write-depth"));
    EXPECT_FALSE(f.g.pass_live("write-id"));
  }
  {
    GraphFixture f;
    f.g.present(add_edges_pass(f.g, f.r, all_kinds()));
    f.g.execute();
    EXPECT_EQ(f.ran, "normal;depth;id;color;");
  }
}

TEST(Edges, WritesLookImagesWhenAsked) {
  const char* dir = std::getenv("SYLVA_EDGES_LOOK_DIR");
  if (dir == nullptr) GTEST_SKIP() << "set SYLVA_EDGES_LOOK_DIR to write the look images";
  const EdgeImages in = render(CubeScene{.sphere = true}, 1024);
  EdgeParams p;
  p.crease = true;
  const cv::Mat lines = detect_edges(in, p);
  cv::Mat ink;
  lines.convertTo(ink, CV_8UC1, -255.0, 255.0);
  EXPECT_TRUE(cv::imwrite(std::string(dir) + "/cube-edges.png", ink));
  // Pen drawing over a light wash on grained paper.
  InkParams look;
  ASSERT_TRUE(parse_hex_color("#f4ecd8", look.paper.color));
  ASSERT_TRUE(parse_hex_color("#1e1a16", look.line_color));
  look.paper.grain = 0.6f;
  look.fill = 0.3f;
  EXPECT_TRUE(
      cv::imwrite(std::string(dir) + "/cube-ink.png",
                  composite_ink(lines, in.color, make_paper(lines.size(), look.paper), look)));
  p.depth_width = 4.0f;
  p.fade = 0.6f;
  p.width = 4.0f;
  detect_edges(in, p).convertTo(ink, CV_8UC1, -255.0, 255.0);
  EXPECT_TRUE(cv::imwrite(std::string(dir) + "/cube-edges-depth.png", ink));
}

}  // namespace
}  // namespace sylva::test
