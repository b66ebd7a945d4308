// The wood drawn where it is seen (passes/seen_wood.h, passes/wood_lines.h) on a synthetic
// frame: a trunk behind a sparse crown. Its outline is drawn wherever the trunk is seen,
// through the gaps between the leaves too, and not across the leaves standing in front of it;
// a leaf lying on the branch (within kWoodCover of it) does not cut it; lines lie on the wood's
// side of its edge; the result is finite and deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

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

TEST(WoodLines, SameFrameSameStrokes) {
  const TrunkFrame f;
  const StrokeDrawing a = draw(f), b = draw(f);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i)
    EXPECT_EQ(a.strokes[i].points, b.strokes[i].points);
}

}  // namespace
}  // namespace sylva::test
