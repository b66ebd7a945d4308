// Where the watercolor paints the wood it sees (passes/watercolor_light.h seen_wood): branches at
// least 5 px wide at 1024 px, measured in 1024 px at every picture size, so a 2048 px picture
// paints the branches a 1024 px one does; and no speck of wood under 60 px at 1024 px.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "passes/watercolor_light.h"

namespace sylva::test {
namespace {

using watercolor_internal::seen_wood;

constexpr int32_t kWood = 7;

// An id image of `size` px with a vertical branch `width` px wide and 0.6 of the height long,
// and a square speck of `speck` px a side, both of the wood cluster; leaves (id 3) elsewhere.
cv::Mat branch_and_speck(int size, int width, int speck) {
  cv::Mat id(size, size, CV_32SC1, cv::Scalar(3));
  id(cv::Rect(size / 4, size / 5, width, size * 3 / 5)).setTo(kWood);
  id(cv::Rect(size * 3 / 4, size / 2, speck, speck)).setTo(kWood);
  return id;
}

bool painted(const cv::Mat& seen, cv::Point at) {
  return seen.at<uint8_t>(at) > 127;
}

TEST(WatercolorWood, TheSameBranchesAtEverySize) {
  for (const int size : {1024, 2048}) {
    const double scale = size / 1024.0;
    // A branch 4 px wide at 1024 px is a twig: not painted at 1024 px nor at 2048 px (where the
    // rounded disc of the old opening, 3.5 px at 1024 px, kept it in dotted pieces).
    const cv::Mat thin = seen_wood(branch_and_speck(size, int(4 * scale), 1), kWood, scale);
    EXPECT_FALSE(painted(thin, {size / 4 + int(2 * scale), size / 2})) << size;
    // One 8 px wide is a branch at both sizes.
    const cv::Mat wide = seen_wood(branch_and_speck(size, int(8 * scale), 1), kWood, scale);
    EXPECT_TRUE(painted(wide, {size / 4 + int(4 * scale), size / 2})) << size;
  }
}

TEST(WatercolorWood, SpecksOfWoodAreNotPainted) {
  for (const int size : {1024, 2048}) {
    const double scale = size / 1024.0;
    // 7 x 7 px at 1024 px (49 px): a speck; 10 x 10 (100 px): a piece of branch.
    const cv::Mat small =
        seen_wood(branch_and_speck(size, int(8 * scale), int(7 * scale)), kWood, scale);
    EXPECT_FALSE(painted(small, {size * 3 / 4 + int(3 * scale), size / 2 + int(3 * scale)}))
        << size;
    const cv::Mat big =
        seen_wood(branch_and_speck(size, int(8 * scale), int(10 * scale)), kWood, scale);
    EXPECT_TRUE(painted(big, {size * 3 / 4 + int(5 * scale), size / 2 + int(5 * scale)})) << size;
  }
}

}  // namespace
}  // namespace sylva::test
