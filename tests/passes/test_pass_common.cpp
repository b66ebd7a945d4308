// Shared pass conventions: the reference-resolution scale; the linear-time sort of unit keys
// gives std::sort's order; the normalised blur averages the values over their weight.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "passes/pass_common.h"

namespace sylva::test {
namespace {

TEST(PassCommon, ReferenceScaleFollowsTheShorterSide) {
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(1024, 1024)), 1.0);
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(4096, 2048)), 2.0);
  EXPECT_DOUBLE_EQ(reference_scale(cv::Size(256, 512)), 0.25);
}

TEST(PassCommon, UnitKeysSortAsStdSortDoes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<std::pair<float, size_t>> pairs;
  for (size_t i = 0; i < 20000; ++i) {
    // Ties (a tenth of the keys repeat a few values), keys one bin apart, the ends and beyond.
    float key = i % 10 == 0 ? float(i % 3) * 0.25f : unit(rng);
    if (i % 97 == 0) key = 1e-6f * float(i % 5);
    if (i == 5) key = 1.0f;
    if (i == 6) key = -0.5f;
    if (i == 7) key = 3.0f;
    pairs.emplace_back(key, i);
  }
  std::shuffle(pairs.begin(), pairs.end(), rng);
  std::vector<std::pair<float, size_t>> expected = pairs;
  std::sort(expected.begin(), expected.end());
  sort_unit_keys(pairs);
  EXPECT_EQ(pairs, expected);
  std::vector<std::pair<float, size_t>> none;
  sort_unit_keys(none);
  EXPECT_TRUE(none.empty());
}

TEST(PassCommon, TheNormalisedBlurAveragesTheValuesOverTheirWeight) {
  // A value of 0.8 over the left half only: blurred over where it is, it stays 0.8 there (the
  // paper's zeros on the right do not dilute it), and the result is the same at every sigma.
  cv::Mat weight(32, 32, CV_32FC1, cv::Scalar(0)), values;
  weight.colRange(0, 16).setTo(1.0f);
  values = weight * 0.8f;
  for (const double sigma : {0.1, 2.0, 8.0}) {
    const cv::Mat out = normalised_blur(values, weight, sigma);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 16; ++x)
        ASSERT_NEAR(out.at<float>(y, x), 0.8f, 1e-4f) << sigma;
  }
}

}  // namespace
}  // namespace sylva::test
