// Pen hatching in parallel groups (passes/hatch_groups.h) on a synthetic leaf layer: one clump
// facing the viewer is hatched by straight strokes all at pen.angle (and the crossing layer at
// 90 degrees to it where the tone passes pen.cross), lying on lines evenly pen.spacing apart;
// the density of lines grows with the tone and none are drawn where the tone is under
// pen.lightest; wood is hatched along its axis; the result is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "passes/hatch_groups.h"

namespace sylva::test {
namespace {

constexpr int kSize = 256;

// One clump (cluster 5): a disc of radius 90 px of primitive 1, ranked `rank` everywhere; a
// vertical bar of wood at x in [20, 34) when `wood`.
LeafLayer clump_layer(float rank, bool wood = false) {
  LeafLayer l;
  l.factor = 1.0;
  l.drawing.size = {kSize, kSize};
  l.front = cv::Mat(kSize, kSize, CV_32SC1, cv::Scalar(0));
  cv::circle(l.front, {128, 128}, 90, cv::Scalar(1), cv::FILLED);
  if (wood) l.front(cv::Rect(20, 10, 14, 230)).setTo(kWoodFront);
  l.depth = cv::Mat(kSize, kSize, CV_32FC1, cv::Scalar(5));
  l.rank = cv::Mat(kSize, kSize, CV_32FC1, cv::Scalar(0));
  l.rank.setTo(rank, l.front > 0);
  l.clusters = {5};
  l.centres = {{128, 128}};
  l.areas = {1.0f};
  return l;
}

cv::Mat facing_normals() {
  return cv::Mat(kSize, kSize, CV_32FC3, cv::Scalar(0, 0, 1));
}

cv::Mat grey() {
  return cv::Mat(kSize, kSize, CV_8UC4, cv::Scalar(100, 100, 100, 255));
}

double angle_of(const Stroke& s) {  // degrees, counter-clockwise from +x (y down), in [0, 180)
  const glm::vec2 d = s.points.back() - s.points.front();
  double a = std::atan2(-d.y, d.x) * 180.0 / std::numbers::pi;
  return a < 0.0 ? a + 180.0 : (a >= 180.0 ? a - 180.0 : a);
}

TEST(HatchGroups, AClumpIsHatchedInParallelStrokesOnEvenlySpacedLines) {
  PenParams p;
  p.tone = PenTone::Hatching;
  p.cross = 1.0f;  // one layer
  const StrokeDrawing d = hatch_groups(clump_layer(0.9f), facing_normals(), grey(), p, 10.0);
  ASSERT_GT(d.strokes.size(), 20u);
  const double phi = p.angle * std::numbers::pi / 180.0;
  const glm::vec2 across(float(std::sin(phi)), float(std::cos(phi)));  // y down
  const double spacing =
      p.spacing * kSize / 1024.0 * std::max(1.0, 4.0 * 1.0 / (p.spacing * kSize / 1024.0));
  for (const Stroke& s : d.strokes) {
    EXPECT_EQ(s.cls, LineClass::Tone);
    ASSERT_GE(s.points.size(), 2u);
    if (glm::length(s.points.back() - s.points.front()) < 4.0f) continue;
    EXPECT_NEAR(angle_of(s), p.angle, 2.0);
    // Every stroke on a line k x spacing from the clump's anchor.
    const double offset = glm::dot(s.points.front() - glm::vec2(128, 128), across) / spacing;
    EXPECT_NEAR(offset, std::round(offset), 0.1) << offset;
  }
}

TEST(HatchGroups, MoreToneMoreLinesAndNoneWhereLight) {
  PenParams p;
  p.tone = PenTone::Hatching;
  p.cross = 1.0f;
  auto ink_of = [&](float rank) {
    const StrokeDrawing d = hatch_groups(clump_layer(rank), facing_normals(), grey(), p, 10.0);
    double length = 0.0;
    for (const Stroke& s : d.strokes)
      for (size_t i = 1; i < s.points.size(); ++i)
        length += glm::length(s.points[i] - s.points[i - 1]);
    return length;
  };
  EXPECT_EQ(ink_of(p.lightest * 0.5f), 0.0);
  const double mid = ink_of(0.6f), dark = ink_of(0.97f);
  EXPECT_GT(mid, 0.0);
  EXPECT_GT(dark, 1.5 * mid);
}

TEST(HatchGroups, TheDarkestCrossesAndWoodIsHatchedAlongItsAxis) {
  PenParams p;
  p.tone = PenTone::Hatching;
  p.cross = 0.5f;
  const StrokeDrawing d = hatch_groups(clump_layer(0.98f, true), facing_normals(), grey(), p, 10.0);
  int along = 0, across = 0, vertical_on_wood = 0, wood = 0;
  for (const Stroke& s : d.strokes) {
    if (glm::length(s.points.back() - s.points.front()) < 4.0f) continue;
    const double a = angle_of(s);
    const bool on_bar = std::all_of(s.points.begin(), s.points.end(),
                                    [](const glm::vec2& q) { return q.x < 36.0f; });
    if (on_bar) {  // the wood bar
      ++wood;
      vertical_on_wood += std::abs(a - 90.0) < 3.0;
      continue;
    }
    along += std::abs(a - p.angle) < 2.0;
    across += std::abs(a - (p.angle + 90.0)) < 2.0 || std::abs(a - (p.angle - 90.0)) < 2.0;
  }
  EXPECT_GT(along, 10);
  EXPECT_GT(across, 10);
  // The wood's grey is even: half of it ranks dark enough to hatch, all along the bar.
  EXPECT_GT(wood, 0);
  EXPECT_EQ(vertical_on_wood, wood);
}

TEST(HatchGroups, SameLayerSameStrokes) {
  PenParams p;
  p.tone = PenTone::Hatching;
  const StrokeDrawing a = hatch_groups(clump_layer(0.8f, true), facing_normals(), grey(), p, 10);
  const StrokeDrawing b = hatch_groups(clump_layer(0.8f, true), facing_normals(), grey(), p, 10);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (size_t i = 0; i < a.strokes.size(); ++i)
    EXPECT_EQ(a.strokes[i].points, b.strokes[i].points);
}

}  // namespace
}  // namespace sylva::test
