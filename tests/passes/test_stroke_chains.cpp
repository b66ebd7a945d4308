// Chaining marks into polylines (passes/crack_chains.h, passes/skeleton_chains.h) and the
// picture-scale abstraction (passes/ink_abstraction.h): a region's outline is one closed
// chain, a T-junction gives a bar and a stem, smoothing keeps open ends, a thick line thins to
// one centre line, closing fills gaps below the detail and opening drops bumps below it while
// long thin parts are kept apart, the depth median keeps steps, and majority labels smooth
// region borders.
#include <gtest/gtest.h>

#include <map>

#include <opencv2/imgproc.hpp>

#include "passes/crack_chains.h"
#include "passes/ink_abstraction.h"
#include "passes/skeleton_chains.h"

namespace sylva::test {
namespace {

// The cracks around the non-zero pixels of `mask`.
Cracks outline(const cv::Mat& mask) {
  Cracks c(mask.size());
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x) {
      if (x + 1 < mask.cols && (mask.at<uint8_t>(y, x) != 0) != (mask.at<uint8_t>(y, x + 1) != 0))
        c.x.at<uint8_t>(y, x) = 255;
      if (y + 1 < mask.rows && (mask.at<uint8_t>(y, x) != 0) != (mask.at<uint8_t>(y + 1, x) != 0))
        c.y.at<uint8_t>(y, x) = 255;
    }
  return c;
}

TEST(CrackChains, ASquaresOutlineIsOneClosedChain) {
  cv::Mat mask = cv::Mat::zeros(20, 20, CV_8UC1);
  mask(cv::Rect(5, 6, 8, 4)).setTo(255);
  const std::vector<Polyline> chains = chain_cracks(outline(mask));
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_TRUE(chains[0].closed);
  EXPECT_EQ(chains[0].points.size(), 2u * (8 + 4));  // one corner per unit of perimeter
  EXPECT_DOUBLE_EQ(polyline_length(chains[0]), 2.0 * (8 + 4));
  for (const cv::Point2f& p : chains[0].points) {  // on the square's corners' lattice
    EXPECT_TRUE(p.x >= 5 && p.x <= 13 && p.y >= 6 && p.y <= 10);
    EXPECT_TRUE(p.x == 5 || p.x == 13 || p.y == 6 || p.y == 10);
  }
}

TEST(CrackChains, ADiscIsOneClosedChainAndTwoRegionsTwo) {
  cv::Mat mask = cv::Mat::zeros(64, 64, CV_8UC1);
  cv::circle(mask, {20, 20}, 10, cv::Scalar(255), cv::FILLED);
  EXPECT_EQ(chain_cracks(outline(mask)).size(), 1u);
  cv::circle(mask, {48, 48}, 6, cv::Scalar(255), cv::FILLED);
  const std::vector<Polyline> chains = chain_cracks(outline(mask));
  ASSERT_EQ(chains.size(), 2u);
  EXPECT_TRUE(chains[0].closed && chains[1].closed);
}

TEST(CrackChains, ATJunctionGivesABarAndAStem) {
  Cracks c(cv::Size(20, 20));
  for (int x = 2; x < 12; ++x)
    c.y.at<uint8_t>(9, x) = 255;  // the bar: y = 10 from x = 2 to 12
  for (int y = 10; y < 16; ++y)
    c.x.at<uint8_t>(y, 6) = 255;  // the stem: x = 7 from y = 10 down to 16
  std::vector<Polyline> chains = chain_cracks(c);
  ASSERT_EQ(chains.size(), 2u);
  std::sort(chains.begin(), chains.end(),
            [](const Polyline& a, const Polyline& b) { return a.points.size() > b.points.size(); });
  EXPECT_DOUBLE_EQ(polyline_length(chains[0]), 10.0);  // straight through the junction
  EXPECT_DOUBLE_EQ(polyline_length(chains[1]), 6.0);
  EXPECT_FALSE(chains[0].closed || chains[1].closed);
}

TEST(CrackChains, NothingMarkedNothingChained) {
  EXPECT_TRUE(chain_cracks(Cracks(cv::Size(8, 8))).empty());
  EXPECT_TRUE(chain_cracks(Cracks(cv::Size(1, 1))).empty());
}

TEST(Polylines, SmoothingKeepsOpenEndsAndShrinksNoStraightLine) {
  Polyline stair;
  for (int i = 0; i < 20; ++i) {
    stair.points.emplace_back(float(i), float(i / 2));
  }
  const Polyline s = smooth_polyline(stair, 2.0);
  EXPECT_EQ(s.points.front(), stair.points.front());
  EXPECT_EQ(s.points.back(), stair.points.back());
  // The staircase about y = x / 2 - 0.25 comes out within 0.3 px of that line.
  for (size_t i = 3; i + 3 < s.points.size(); ++i)
    EXPECT_NEAR(s.points[i].y, s.points[i].x / 2.0 - 0.25, 0.3) << i;
  const Polyline line = simplify_polyline(s, 0.5);
  EXPECT_LE(line.points.size(), 4u);
  EXPECT_EQ(smooth_polyline(stair, 0.0).points, stair.points);
}

TEST(SkeletonChains, AThickLineThinsToOneCentreLine) {
  cv::Mat mask = cv::Mat::zeros(40, 80, CV_8UC1);
  cv::line(mask, {10, 20}, {70, 20}, cv::Scalar(255), 5);
  const std::vector<Polyline> chains = skeleton_chains(mask, 3.0);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_GT(polyline_length(chains[0]), 55.0);
  for (const cv::Point2f& p : chains[0].points)
    EXPECT_NEAR(p.y, 20.5f, 1.01f);
  EXPECT_TRUE(skeleton_chains(cv::Mat::zeros(10, 10, CV_8UC1), 3.0).empty());
}

TEST(SkeletonChains, ARingIsAClosedChain) {
  cv::Mat mask = cv::Mat::zeros(60, 60, CV_8UC1);
  cv::circle(mask, {30, 30}, 20, cv::Scalar(255), 3);
  const std::vector<Polyline> chains = skeleton_chains(mask, 3.0);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_TRUE(chains[0].closed);
  // An 8-connected digital circle is up to ~15 % longer than the true one.
  EXPECT_NEAR(polyline_length(chains[0]), 1.07 * 2 * 3.14159 * 20, 0.1 * 2 * 3.14159 * 20);
}

TEST(CrownShape, ClosingFillsGapsAndOpeningDropsBumpsBelowTheDetail) {
  cv::Mat plant = cv::Mat::zeros(100, 100, CV_8UC1);
  plant(cv::Rect(20, 20, 25, 50)).setTo(255);
  plant(cv::Rect(48, 20, 25, 50)).setTo(255);  // a 3 px gap
  plant(cv::Rect(73, 40, 4, 4)).setTo(255);    // a 4 px bump
  const CrownShape s = crown_shape(plant, 10.0);
  EXPECT_EQ(s.body.at<uint8_t>(45, 46), 255);  // gap filled
  EXPECT_EQ(s.body.at<uint8_t>(42, 75), 0);    // bump gone
  EXPECT_EQ(s.thin.at<uint8_t>(42, 75), 0);    // and too short to be a thin part
  EXPECT_EQ(s.body.at<uint8_t>(40, 30), 255);
  // Below 2 px nothing is simplified.
  const CrownShape exact = crown_shape(plant, 1.0);
  EXPECT_EQ(cv::countNonZero(exact.body != plant), 0);
  EXPECT_EQ(cv::countNonZero(exact.thin), 0);
}

TEST(CrownShape, LongThinPartsAreKeptApart) {
  cv::Mat plant = cv::Mat::zeros(120, 100, CV_8UC1);
  plant(cv::Rect(20, 10, 60, 40)).setTo(255);
  plant(cv::Rect(48, 50, 4, 60)).setTo(255);  // a hanging strand, 4 px wide and 60 long
  const CrownShape s = crown_shape(plant, 10.0);
  EXPECT_EQ(s.body.at<uint8_t>(80, 50), 0);
  EXPECT_EQ(s.thin.at<uint8_t>(80, 50), 255);
  EXPECT_EQ(s.thin.at<uint8_t>(30, 50), 0);
}

TEST(MedianDepth, KeepsStepsAndDropsSpecks) {
  cv::Mat depth(60, 60, CV_32FC1, cv::Scalar(10.0f)), plant(60, 60, CV_8UC1, cv::Scalar(255));
  depth(cv::Rect(30, 0, 30, 60)).setTo(20.0f);  // a step
  depth.at<float>(10, 10) = 20.0f;              // a speck
  float near = 0, far = 0;
  const cv::Mat m = median_depth(depth, plant, 5.0, near, far);
  EXPECT_FLOAT_EQ(near, 10.0f);
  EXPECT_FLOAT_EQ(far, 20.0f);
  EXPECT_EQ(m.at<uint8_t>(10, 10), 1);  // the near level
  EXPECT_EQ(m.at<uint8_t>(30, 20), 1);
  EXPECT_EQ(m.at<uint8_t>(30, 40), 254);  // the far level, the step sharp
  EXPECT_EQ(m.at<uint8_t>(30, 29), 1);
  EXPECT_EQ(m.at<uint8_t>(30, 30), 254);
  plant.setTo(0);
  EXPECT_EQ(median_depth(depth, plant, 5.0, near, far).at<uint8_t>(5, 5), kNoDepth);
}

TEST(MajorityLabels, SmoothsABorderAndKeepsBackground) {
  cv::Mat labels(40, 40, CV_32SC1, cv::Scalar(1));
  labels(cv::Rect(20, 0, 20, 40)).setTo(2);
  labels.at<int>(10, 5) = 2;  // a stray pixel of 2 inside 1
  labels.at<int>(0, 0) = 0;
  const cv::Mat m = majority_labels(labels, 2);
  EXPECT_EQ(m.at<int>(10, 5), 1);
  EXPECT_EQ(m.at<int>(10, 19), 1);
  EXPECT_EQ(m.at<int>(10, 20), 2);
  EXPECT_EQ(m.at<int>(0, 0), 0);
}

// The header's rule, counted over the whole window at every pixel (majority_labels skips the
// windows that hold one label only).
int majority_by_count(const cv::Mat& labels, int y, int x, int r) {
  const int own = labels.at<int>(y, x);
  if (own == 0) return 0;
  std::map<int, int> counts;
  for (int v = std::max(0, y - r); v <= std::min(labels.rows - 1, y + r); ++v)
    for (int u = std::max(0, x - r); u <= std::min(labels.cols - 1, x + r); ++u)
      if (const int l = labels.at<int>(v, u); l != 0) ++counts[l];
  int most = 0;
  for (const auto& [l, n] : counts)
    most = std::max(most, n);
  if (counts[own] == most) return own;  // a tie keeps the pixel's own
  for (const auto& [l, n] : counts)     // else the smallest label of the most frequent
    if (n == most) return l;
  return own;
}

TEST(MajorityLabels, IsTheCountOverEveryWindow) {
  cv::Mat noise(90, 70, CV_32FC1);
  cv::randu(noise, 0.0f, 1.0f);
  cv::GaussianBlur(noise, noise, {0, 0}, 2.0);
  cv::Mat labels(noise.size(), CV_32SC1);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)  // patches of 0 and 1..5 with ragged borders
      labels.at<int>(y, x) = int(noise.at<float>(y, x) * 60.0f) % 6 * (1 + (x * 7 + y) % 3 / 2);
  for (int r : {0, 1, 3, 6}) {
    const cv::Mat m = majority_labels(labels, r);
    int wrong = 0;
    for (int y = 0; y < labels.rows; ++y)
      for (int x = 0; x < labels.cols; ++x)
        wrong += m.at<int>(y, x) != majority_by_count(labels, y, x, r);
    EXPECT_EQ(wrong, 0) << "radius " << r;
  }
}

}  // namespace
}  // namespace sylva::test
