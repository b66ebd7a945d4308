// Edges, line drawing: the width scales with the resolution; lines are antialiased and even in
// width in every direction; width and opacity follow depth; min_width keeps small lines dark
// and floors only; the same input gives the same bytes at any thread count; the graph reads only
// what the enabled kinds need. Scenes from tests/passes/edge_scenes.h; scripts/look.sh writes
// the cube's lines as PNGs for a visual check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "passes/composite.h"
#include "passes/edges.h"
#include "tests/passes/edge_scenes.h"

namespace sylva::test {
namespace {

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
  p.min_width = 0.0f;  // half-pixel lines too
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

// The darkest coverage across the vertical crease below the cube's centre, averaged over rows.
double vertical_crease_darkness(const cv::Mat& lines) {
  const int s = lines.rows;
  const int half = std::max(4, int(0.05 * s));
  double total = 0.0;
  int rows = 0;
  for (int y = s / 2 + s / 16; y < s / 2 + s / 8; ++y, ++rows) {
    double darkest = 0.0;
    cv::minMaxLoc(lines(cv::Rect(s / 2 - half, y, 2 * half, 1)), nullptr, &darkest);
    total += darkest;
  }
  return total / rows;
}

TEST(Edges, MinWidthKeepsSmallLinesDark) {
  // edges.width 2 is 0.5 px at 256 px: no pixel is more than half covered, a light grey.
  EdgeParams p;
  p.width = 2.0f;
  const EdgeImages small = render(CubeScene{}, 256);
  p.min_width = 0.0f;
  const cv::Mat thin = detect_edges(small, p);
  EXPECT_NEAR(vertical_crease_width(thin), 0.5, 0.1);
  EXPECT_LT(vertical_crease_darkness(thin), 0.55);
  p.min_width = 1.5f;
  const cv::Mat floored = detect_edges(small, p);
  EXPECT_NEAR(vertical_crease_width(floored), 1.5, 0.15);
  EXPECT_GT(vertical_crease_darkness(floored), 0.74);  // every row has a pixel at least 3/4 ink
  p.min_width = 4.0f;                                  // the top of the range
  EXPECT_NEAR(vertical_crease_width(detect_edges(small, p)), 4.0, 0.3);
  // A floor, not a scale: where the line is wider anyway (2 px at 1024), nothing changes.
  const EdgeImages big = render(CubeScene{}, 1024);
  p.min_width = 0.0f;
  const cv::Mat free_width = detect_edges(big, p);
  p.min_width = 1.5f;
  EXPECT_EQ(cv::countNonZero(detect_edges(big, p) != free_width), 0);
}

TEST(Edges, MinWidthFloorsTheFarthestLinesOfDepthWidth) {
  const int s = 256;
  EdgeImages in;
  in.depth = cv::Mat::zeros(s, s, CV_32FC1);
  in.depth(cv::Rect(20, 40, 80, 160)).setTo(2.0f);
  in.depth(cv::Rect(150, 40, 80, 160)).setTo(8.0f);
  EdgeParams p = only(&EdgeParams::silhouette);
  p.width = 16.0f;  // 4 px at 256
  p.depth_width = 4.0f;
  p.min_width = 2.0f;
  const cv::Mat lines = detect_edges(in, p);
  auto width_at = [&](int x0, int x1) {
    double w = 0.0;
    for (int x = x0; x < x1; ++x)
      w += lines.at<float>(120, x);
    return w;
  };
  EXPECT_NEAR(width_at(5, 35), 4.0, 0.1);     // near: full width
  EXPECT_NEAR(width_at(135, 165), 2.0, 0.1);  // far: 1 px, floored at 2
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

TEST(Edges, SameBytesAtAnyThreadCount) {
  // The pass works in parallel row bands; no pixel may depend on how they fall. Seeded specks
  // in the normals give min_length groups to drop all over the image.
  EdgeImages in = render(CubeScene{.sphere = true}, 300);
  cv::RNG rng(11);
  for (int k = 0; k < 400; ++k) {
    const int x = rng.uniform(0, 298), y = rng.uniform(0, 299);
    in.normal(cv::Rect(x, y, 2, 1)).setTo(cv::Scalar(0.6f, -0.8f, 0.0f));
  }
  EdgeParams p = all_kinds();
  p.depth_width = 3.0f;
  p.fade = 0.4f;
  p.min_width = 1.2f;
  p.min_length = 24.0f;
  const cv::Mat any = detect_edges(in, p);
  EdgeParams keep_all = p;
  keep_all.min_length = 0.0f;
  ASSERT_LT(count(mark_edges(in, p)), count(mark_edges(in, keep_all)));  // not vacuous
  // More threads than bands of some passes, then one (in this order: once limited to one
  // thread, TBB ignores requests for more).
  const int threads = cv::getNumThreads();
  cv::setNumThreads(7);
  const cv::Mat seven = detect_edges(in, p);
  cv::setNumThreads(1);
  const cv::Mat one = detect_edges(in, p);
  cv::setNumThreads(threads);
  ASSERT_EQ(one.size(), seven.size());
  EXPECT_EQ(std::memcmp(one.data, seven.data, one.total() * one.elemSize()), 0);
  EXPECT_EQ(std::memcmp(one.data, any.data, one.total() * one.elemSize()), 0);
}

TEST(Edges, ImagesOneOrTwoPixelsAcrossGiveValidOutput) {
  // The lattice's borders: images too narrow for some kinds of mark.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(1, 9), cv::Size(9, 1), cv::Size(2, 2)}) {
    EdgeImages in;
    in.depth = cv::Mat(size, CV_32FC1, cv::Scalar(1.0f));
    in.depth.at<float>(0, 0) = 3.0f;
    in.normal = cv::Mat(size, CV_32FC3, cv::Scalar(0.0f, 0.0f, 1.0f));
    in.id = cv::Mat(size, CV_32SC1, cv::Scalar(2));
    in.color = cv::Mat(size, CV_8UC4, cv::Scalar(90, 90, 90, 255));
    in.color.at<cv::Vec4b>(size.height - 1, size.width - 1)[3] = 0;
    EdgeParams p = all_kinds();
    p.depth_width = 2.0f;
    const cv::Mat lines = detect_edges(in, p);
    EXPECT_EQ(lines.size(), size);
    EXPECT_TRUE(in_unit_range(lines)) << size;
  }
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
    r.normal = g.resource<cv::Mat>("normal");
    r.depth = g.resource<cv::Mat>("depth");
    r.id = g.resource<cv::Mat>("id");
    r.color = g.resource<cv::Mat>("color");
    const std::pair<ImageHandle, cv::Mat> writers[] = {{r.normal, images.normal},
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
    no_color.color = {};
    const auto out = add_edges_pass(f.g, no_color, p);
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

}  // namespace
}  // namespace sylva::test
