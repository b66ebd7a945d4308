// passes/thinning.h against OpenCV's cv::ximgproc::thinning(THINNING_ZHANGSUEN): the same
// skeleton, pixel for pixel, on shapes of every kind the ink thins (strands, blobs, rings,
// shapes touching the image's border) and on random masks.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <random>

#include "passes/thinning.h"

namespace sylva::test {
namespace {

cv::Mat reference(const cv::Mat& mask) {
  cv::Mat out;
  cv::ximgproc::thinning(mask, out, cv::ximgproc::THINNING_ZHANGSUEN);
  return out;
}

void expect_same(const cv::Mat& mask, const std::string& what) {
  const cv::Mat ours = thin_zhang_suen(mask);
  const cv::Mat theirs = reference(mask);
  ASSERT_EQ(ours.type(), CV_8UC1) << what;
  EXPECT_EQ(cv::countNonZero(ours != theirs), 0) << what;
  EXPECT_GT(cv::countNonZero(ours), 0) << what;
  EXPECT_LE(cv::countNonZero(ours), cv::countNonZero(mask)) << what;
}

TEST(Thinning, DrawnShapesMatchOpenCv) {
  cv::Mat m(120, 160, CV_8UC1, cv::Scalar(0));
  cv::line(m, {10, 10}, {150, 100}, 255, 7);
  cv::circle(m, {60, 80}, 25, 255, 5);
  cv::rectangle(m, {100, 10}, {150, 40}, 255, cv::FILLED);
  cv::ellipse(m, {30, 60}, {20, 8}, 30, 0, 360, 255, cv::FILLED);
  expect_same(m, "strokes, a ring, a block and an ellipse");
  cv::Mat border(40, 40, CV_8UC1, cv::Scalar(0));
  cv::rectangle(border, {0, 0}, {39, 12}, 255, cv::FILLED);  // touches three sides
  expect_same(border, "a bar along the border");
}

TEST(Thinning, RandomMasksMatchOpenCv) {
  std::mt19937 rng(7);
  for (int i = 0; i < 12; ++i) {
    cv::Mat noise(64 + 16 * i, 80, CV_8UC1);
    cv::randu(noise, 0, 256);
    cv::GaussianBlur(noise, noise, {0, 0}, 1.0 + 0.5 * (i % 4));
    cv::Mat mask = noise > 128 + int(rng() % 8);
    expect_same(mask, "random mask " + std::to_string(i));
  }
}

TEST(Thinning, EmptyAndSinglePixels) {
  const cv::Mat empty(10, 10, CV_8UC1, cv::Scalar(0));
  EXPECT_EQ(cv::countNonZero(thin_zhang_suen(empty)), 0);
  cv::Mat dot = empty.clone();
  dot.at<uint8_t>(5, 5) = 1;  // any non-zero value is on
  EXPECT_EQ(cv::countNonZero(thin_zhang_suen(dot) != reference(dot != 0)), 0);
  EXPECT_EQ(thin_zhang_suen(dot).at<uint8_t>(5, 5), 255);
}

}  // namespace
}  // namespace sylva::test
