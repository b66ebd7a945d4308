// The tone rank's smoothed darkness: read only at points (unranked) with a wide Gaussian, it is
// smoothed at half the working size and read bilinearly, and reads as the full-size one does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "passes/tone_rank.h"

namespace sylva::test {
namespace {

// A 200 x 160 plant (an ellipse, alpha 255) whose grey brightens to the right and down, with a
// pixel's noise, on transparent paper.
cv::Mat plant_colour() {
  cv::Mat c(160, 200, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> noise(-30, 30);
  for (int y = 0; y < c.rows; ++y)
    for (int x = 0; x < c.cols; ++x) {
      const double ex = (x - 100.0) / 90.0, ey = (y - 80.0) / 70.0;
      if (ex * ex + ey * ey > 1.0) continue;
      const int g = std::clamp(40 + x + y / 2 + noise(rng), 0, 255);
      c.at<cv::Vec4b>(y, x) = cv::Vec4b(uint8_t(g), uint8_t(g), uint8_t(g), 255);
    }
  return c;
}

TEST(ToneRank, UnrankedWithAWideGaussianReadsAsTheFullSizeDoes) {
  const cv::Mat colour = plant_colour();
  const cv::Size work(120, 96);  // a non-integer working scale, as the ink frame's
  const ToneRank full = tone_rank(colour, work, 6.0, true);
  const ToneRank half = tone_rank(colour, work, 6.0, false);
  ASSERT_EQ(full.dark.size(), work);
  EXPECT_EQ(half.dark.size(), cv::Size(60, 48));
  EXPECT_EQ(cv::norm(full.darkness, half.darkness, cv::NORM_INF), 0.0);  // not smoothed: the same
  double most = 0.0, sum = 0.0;
  int n = 0;
  for (int y = 0; y < work.height; ++y)
    for (int x = 0; x < work.width; ++x) {
      if (!full.plant.at<uint8_t>(y, x)) continue;
      const cv::Point2f at(float(x) + 0.5f, float(y) + 0.5f);
      const double d = std::abs(full.dark_near(at) - half.dark_near(at));
      most = std::max(most, d);
      sum += d;
      ++n;
    }
  ASSERT_GT(n, 5000);
  EXPECT_LT(most, 0.005);
  EXPECT_LT(sum / n, 0.001);
  // Beyond the image: clamped to its edge, in [0, 1].
  for (const cv::Point2f at : {cv::Point2f(-5.0f, -5.0f), cv::Point2f(1e4f, 1e4f)}) {
    const float v = half.dark_near(at);
    EXPECT_TRUE(v >= 0.0f && v <= 1.0f) << v;
  }
}

TEST(ToneRank, ANarrowGaussianStaysAtTheWorkingSize) {
  const cv::Mat colour = plant_colour();
  const cv::Size work(120, 96);
  const ToneRank full = tone_rank(colour, work, 2.9, true);
  const ToneRank unranked = tone_rank(colour, work, 2.9, false);
  ASSERT_EQ(unranked.dark.size(), work);
  EXPECT_EQ(cv::norm(full.dark, unranked.dark, cv::NORM_INF), 0.0);
  EXPECT_TRUE(unranked.sorted.empty());
  EXPECT_FALSE(full.sorted.empty());
}

}  // namespace
}  // namespace sylva::test
