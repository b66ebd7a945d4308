// Edges, marking: property tests on the analytic G-buffers of tests/passes/edge_scenes.h: a
// tilted plane has no interior edge at any distance; a cube seen corner-on gives its silhouette
// from coverage and its three creases from normals and from second-order depth; counts fall as
// thresholds rise; id boundaries are exact; the vector metric on short (low-ka) normals gives
// fewer lines; min_length drops short fragments, keeps long lines, and scales with the size.
// Line drawing is tested in test_edge_lines.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "passes/edges.h"
#include "tests/passes/edge_scenes.h"

namespace sylva::test {
namespace {

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
  p.normal_metric = NormalMetric::Vector;
  EXPECT_EQ(count(mark_edges(unit, p)), angle_unit);
  // The sphere's normals scaled by ka = 0.3, as realigned-scaled normals deep in a crown.
  const EdgeImages scaled = render(CubeScene{.sphere = true, .ka = 0.3f}, 256);
  p.normal_metric = NormalMetric::Angle;
  const int angle = count(mark_edges(scaled, p));
  p.normal_metric = NormalMetric::Vector;
  const int vector = count(mark_edges(scaled, p));
  EXPECT_EQ(angle, angle_unit);  // the angle metric ignores the length
  EXPECT_LT(vector, angle);
}

// A fronto-parallel surface whose normal turns 90 degrees below the middle row (one long
// horizontal line), and optionally an isolated fragment: three pixels in a row at (size / 4,
// size / 4) with a normal of their own, whose eight marks lie on a 4 x 2 pixel box (extent
// hypot(4, 2) = 4.47 px).
EdgeImages line_and_fragment(int size, bool fragment) {
  EdgeImages in;
  in.normal = cv::Mat(size, size, CV_32FC3, cv::Scalar(0.0f, 0.0f, 1.0f));
  in.normal(cv::Rect(0, size / 2, size, size - size / 2)).setTo(cv::Scalar(1.0f, 0.0f, 0.0f));
  if (fragment) in.normal(cv::Rect(size / 4, size / 4, 3, 1)).setTo(cv::Scalar(0.0f, 1.0f, 0.0f));
  return in;
}

TEST(Edges, MinLengthDropsShortFragmentsAndKeepsLongLines) {
  EdgeParams p = only(&EdgeParams::normal);
  const int line_only = count(mark_edges(line_and_fragment(256, false), p));
  EXPECT_EQ(line_only, 256);
  const EdgeImages in = line_and_fragment(256, true);
  // At 256 px, min_length is a quarter of its value in px: 16 -> 4 px keeps the 4.47 px
  // fragment, 20 -> 5 px drops it; the 256 px line stays even at the top of the range (64 px).
  for (const auto& [min_length, kept] : std::vector<std::pair<float, bool>>{
           {0.0f, true}, {16.0f, true}, {20.0f, false}, {256.0f, false}}) {
    p.min_length = min_length;
    const EdgeMarks marks = mark_edges(in, p);
    EXPECT_EQ(count(marks), line_only + (kept ? 8 : 0)) << min_length;
    if (!kept) {
      EXPECT_TRUE(same_marks(marks, mark_edges(line_and_fragment(256, false), p)));
    }
  }
  // Scaled like the width: at 1024 px, min_length 16 is 16 px, and the same 3-pixel fragment
  // goes.
  p.min_length = 16.0f;
  EXPECT_EQ(count(mark_edges(line_and_fragment(1024, true), p)), 1024);
  p.min_length = 0.0f;
  EXPECT_EQ(count(mark_edges(line_and_fragment(1024, true), p)), 1024 + 8);
}

TEST(Edges, MinLengthKeepsCountsFallingAsThresholdsRise) {
  // Long lines split into shorter groups as the threshold rises, but never grow.
  const EdgeImages in = render(CubeScene{.sphere = true}, 256);
  EdgeParams p = only(&EdgeParams::normal);
  p.min_length = 40.0f;
  int previous = -1;
  for (float v : {2.0f, 5.0f, 10.0f, 20.0f, 45.0f, 90.0f}) {
    p.normal_threshold = v;
    const int c = count(mark_edges(in, p));
    if (previous >= 0) {
      EXPECT_LE(c, previous) << "at " << v;
    }
    previous = c;
  }
}

}  // namespace
}  // namespace sylva::test
