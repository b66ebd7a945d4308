// The wood drawn where it is seen (passes/seen_wood.h, passes/wood_lines.h) on a synthetic
// frame: a trunk behind a sparse crown. Its outline is drawn wherever the trunk is seen,
// through the gaps between the leaves too, and not across the leaves standing in front of it;
// a leaf lying on the branch (within kWoodCover of it) does not cut it; lines lie on the wood's
// side of its edge; the result is finite and deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "core/gl/camera.h"
#include "core/stroke_render.h"
#include "passes/wood_lines.h"

namespace sylva::test {
namespace {

constexpr int kSize = 256;
constexpr int kWood = 7, kLeaf = 3;

// A trunk (x in [112, 144), every row) at depth 10 behind three leaves at depth 6 (discs of
// radius 14 at rows 60, 128 and 196 on the trunk's left edge); paper elsewhere.
struct TrunkFrame {
  cv::Mat id{kSize, kSize, CV_32SC1, cv::Scalar(0)};
  cv::Mat depth{kSize, kSize, CV_32FC1, cv::Scalar(0)};
  cv::Mat leaves{kSize, kSize, CV_8UC1, cv::Scalar(0)};
  explicit TrunkFrame(bool with_leaves = true) {
    id(cv::Rect(112, 0, 32, kSize)).setTo(kWood);
    depth(cv::Rect(112, 0, 32, kSize)).setTo(10.0f);
    if (!with_leaves) return;
    for (int row : {60, 128, 196})
      cv::circle(leaves, {112, row}, 14, cv::Scalar(255), cv::FILLED);
    id.setTo(kLeaf, leaves);
    depth.setTo(6.0f, leaves);
  }
};

StrokeDrawing draw(const TrunkFrame& f, SeenWood* seen_out = nullptr) {
  WoodImages in;
  in.id = f.id;
  in.depth = f.depth;
  const SeenWood seen = seen_wood(in, kWood, 10.0);
  if (seen_out) *seen_out = seen;
  return wood_strokes(seen, InkLineParams{}, EdgeParams{});
}

TEST(WoodLines, TheTrunkIsOutlinedWhereSeenAndNotAcrossTheLeavesInFront) {
  const TrunkFrame f;
  const StrokeDrawing d = draw(f);
  ASSERT_GT(d.strokes.size(), 0u);
  const cv::Mat ink = rasterize_strokes(d) > 0.25f;
  cv::Mat reach;
  cv::distanceTransform(ink == 0, reach, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  // The trunk's two edges wherever no leaf covers them: within 2 px of ink.
  int seen = 0, drawn = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x : {112, 143}) {
      if (f.leaves.at<uint8_t>(y, x)) continue;
      ++seen;
      drawn += reach.at<float>(y, x) <= 2.0f;
    }
  EXPECT_GT(double(drawn) / seen, 0.95);
  // No ink inside the leaves in front (their own outlines are the foliage's, not the wood's).
  cv::Mat inner;
  cv::erode(f.leaves, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
  EXPECT_EQ(cv::countNonZero(ink & inner), 0);
  // The lines lie over the wood: no ink more than a pixel off the trunk (but for round caps
  // where a leaf cuts the edge).
  int off = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      off += ink.at<uint8_t>(y, x) && (x < 110 || x > 145);
  EXPECT_LT(off, 20);
  for (const Stroke& s : d.strokes)
    for (const glm::vec2& q : s.points)
      EXPECT_TRUE(std::isfinite(q.x) && std::isfinite(q.y));
}

TEST(WoodLines, ALeafLyingOnTheBranchDoesNotCutIt) {
  // A needle lying on the trunk (without surface samples, gaps up to 0.3 x ink.detail across
  // are closed): the trunk is seen through it.
  TrunkFrame f(false);
  f.id(cv::Rect(112, 126, 32, 2)).setTo(kLeaf);  // a needle across the trunk
  f.depth(cv::Rect(112, 126, 32, 2)).setTo(9.99f);
  SeenWood seen;
  draw(f, &seen);
  EXPECT_EQ(cv::countNonZero(seen.mask(cv::Rect(114, 126, 28, 2))), 56);  // but the edges
}

TEST(WoodLines, NoWoodClusterNoStrokes) {
  const TrunkFrame f;
  WoodImages in;
  in.id = f.id;
  in.depth = f.depth;
  const SeenWood seen = seen_wood(in, 0, 10.0);
  EXPECT_TRUE(seen.mask.empty());
  const StrokeDrawing d = wood_strokes(seen, InkLineParams{}, EdgeParams{});
  EXPECT_EQ(d.size, cv::Size(kSize, kSize));
  EXPECT_TRUE(d.strokes.empty());
}

TEST(WoodLines, WoodMovedInTheFrameDrawsTheSameStrokesMoved) {
  // A branch with a leaf in front of it, away from the frame's edges, drawn in a frame and again
  // moved by (37, 21) in a larger one: the same strokes, moved (the outline is found around the
  // wood, wherever it lies in the frame).
  auto frame = [](cv::Size size, cv::Point at) {
    TrunkFrame f(false);
    f.id = cv::Mat(size, CV_32SC1, cv::Scalar(0));
    f.depth = cv::Mat(size, CV_32FC1, cv::Scalar(0));
    f.id(cv::Rect(at.x + 100, at.y + 40, 40, 160)).setTo(kWood);
    f.depth(cv::Rect(at.x + 100, at.y + 40, 40, 160)).setTo(10.0f);
    cv::Mat leaf(size, CV_8UC1, cv::Scalar(0));
    cv::circle(leaf, at + cv::Point(100, 120), 14, cv::Scalar(255), cv::FILLED);
    f.id.setTo(kLeaf, leaf);
    f.depth.setTo(6.0f, leaf);
    return f;
  };
  const cv::Point shift(37, 21);
  const StrokeDrawing a = draw(frame({kSize, kSize}, {0, 0}));
  const StrokeDrawing b = draw(frame({kSize + 60, kSize + 40}, shift));
  ASSERT_GT(a.strokes.size(), 0u);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i) {
    ASSERT_EQ(a.strokes[i].points.size(), b.strokes[i].points.size());
    for (size_t k = 0; k < a.strokes[i].points.size(); ++k) {
      EXPECT_NEAR(a.strokes[i].points[k].x + float(shift.x), b.strokes[i].points[k].x, 1e-3f);
      EXPECT_NEAR(a.strokes[i].points[k].y + float(shift.y), b.strokes[i].points[k].y, 1e-3f);
    }
  }
}

TEST(WoodLines, SameFrameSameStrokes) {
  const TrunkFrame f;
  const StrokeDrawing a = draw(f), b = draw(f);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i)
    EXPECT_EQ(a.strokes[i].points, b.strokes[i].points);
}

TEST(WoodLines, ASplatMadeBeforeTheRasterSeesTheSameWood) {
  // The wood's samples (a trunk, 0.05 apart) splatted before the raster (the pass "wood-splat")
  // complete the seen wood exactly as splatting them in seen_wood does, without changing the
  // raster's depth.
  SurfaceSamples samples;
  samples.spacing = 0.05f;
  for (int i = 0; i <= 60; ++i)
    for (int k = 0; k < 8; ++k) {
      const float a = 0.785f * float(k);
      samples.positions.push_back(
          {0.15f * std::cos(a), -1.5f + 0.05f * float(i), 0.15f * std::sin(a)});
      samples.clusters.push_back(uint32_t(kWood));
    }
  samples.normals.assign(samples.size(), glm::vec3(0, 0, 1));
  samples.areas.assign(samples.size(), 0.0025f);
  const Camera camera = make_orbit_camera(Sphere{{0, 0, 0}, 2.0f}, OrbitParams{}, kSize, kSize);
  const WoodSplat splat = wood_splat(samples, camera, kWood);
  ASSERT_EQ(splat.z.size(), cv::Size(kSize, kSize));
  cv::Mat hit = splat.z < std::numeric_limits<float>::infinity();
  EXPECT_GT(cv::countNonZero(hit), 500);  // the trunk's column, every sample a disc
  double lo = 0, hi = 0;
  cv::minMaxLoc(splat.z, &lo, &hi, nullptr, nullptr, hit);
  EXPECT_GT(lo, 0.0);
  EXPECT_TRUE(std::isfinite(hi));
  EXPECT_TRUE(wood_splat(samples, camera, 0).z.empty());  // no wood cluster, no splat
  // Leaves everywhere, from in front of the trunk (left) to behind it (right): where they do
  // not stand clearly in front, the trunk is seen through them.
  cv::Mat id(kSize, kSize, CV_32SC1, cv::Scalar(kLeaf)), depth(kSize, kSize, CV_32FC1);
  for (int x = 0; x < kSize; ++x)
    depth.col(x).setTo(float(lo) - 0.5f + float(hi - lo + 1.0) * float(x) / kSize);
  WoodImages in;
  in.id = id;
  in.depth = depth;
  in.camera = camera;
  in.samples = std::make_shared<const SurfaceSamples>(samples);
  const cv::Mat shown = depth.clone();
  const SeenWood here = seen_wood(in, kWood, 10.0);
  // The raster's depth, which other passes read, is left as it was (the wood's depth is a copy).
  EXPECT_EQ(cv::norm(depth, shown, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(here.depth, shown, cv::NORM_INF), 0.0);
  in.splat = splat;
  const SeenWood before = seen_wood(in, kWood, 10.0);
  EXPECT_GT(cv::countNonZero(here.mask), 500);
  EXPECT_EQ(cv::countNonZero(here.mask != before.mask), 0);
  EXPECT_EQ(cv::countNonZero(here.depth != before.depth), 0);
}

}  // namespace
}  // namespace sylva::test
