// The watercolor's detail layer (passes/watercolor_marks.h) on synthetic leaf pieces seen by an
// orthographic camera: on bare paper each leaf leaves a touch of its own colour where it lands
// and nothing away from the leaves; a long leaf (a willow's) leaves a long touch along it;
// inside a wash the touches add texture without shifting the wash's mean value; dark leaves
// carry more of their colour's pigment than light ones; the seen wood stays bare; the result is
// finite and deterministic. Every parameter at both ends: tests/styles/test_every_parameter.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/imgproc.hpp>

#include "passes/watercolor_marks.h"
#include "tests/passes/front_view.h"

namespace sylva::test {
namespace {

constexpr int kSize = kFrontSize;

// A flat leaf facing the camera, semi-axes rx (along x) and ry (along y).
LeafPiece leaf(glm::vec3 centre, float rx, float ry) {
  LeafPiece p;
  p.centre = centre;
  p.cov[0] = rx * rx / 4.0f;
  p.cov[3] = ry * ry / 4.0f;
  p.area = float(M_PI) * rx * ry;
  p.cluster = 1;
  return p;
}

WatercolorMarkImages images_of(std::vector<LeafPiece> pieces, const cv::Mat& color) {
  auto lp = std::make_shared<LeafPieces>();
  lp->pieces = std::move(pieces);
  lp->cell = 0.05f;
  WatercolorMarkImages in;
  in.pieces = lp;
  in.camera = front_camera();
  in.color = color;
  in.id = cv::Mat(kSize, kSize, CV_32SC1, cv::Scalar(1));
  return in;
}

cv::Mat green(int level = 100) {
  return cv::Mat(kSize, kSize, CV_8UC4, cv::Scalar(60, level, 40, 255));
}

// Small marks at 256 px: the dabs are about 2 px across unless the leaf is bigger.
WatercolorMarkParams params() {
  WatercolorMarkParams p;
  p.strength = 1.0f;
  p.size = 8.0f;
  return p;
}

float density_at(const cv::Mat& d, cv::Point at) {
  const cv::Vec3f v = d.at<cv::Vec3f>(at);
  return v[0] + v[1] + v[2];
}

TEST(WatercolorMarks, ATouchLiesWhereEachLeafLandsAndNowhereElse) {
  const std::vector<LeafPiece> leaves{leaf({-1.0f, 0.0f, 0.0f}, 0.1f, 0.1f),
                                      leaf({1.0f, 0.5f, 0.0f}, 0.1f, 0.1f)};
  cv::Mat density(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(images_of(leaves, green()), params(), density);
  for (const LeafPiece& l : leaves)
    EXPECT_GT(density_at(density, to_px(l.centre)), 0.05f) << "a touch at the leaf";
  EXPECT_EQ(density_at(density, to_px({0.0f, -1.0f, 0.0f})), 0.0f) << "paper away from leaves";
  EXPECT_EQ(density_at(density, to_px({-1.0f, 1.0f, 0.0f})), 0.0f);
  EXPECT_TRUE(cv::checkRange(density));
}

TEST(WatercolorMarks, ALongLeafLeavesALongTouch) {
  // A hanging leaf (a willow's), 0.6 units long and 0.05 wide.
  cv::Mat density(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(images_of({leaf({0.0f, 0.0f, 0.0f}, 0.05f, 0.6f)}, green()), params(), density);
  cv::Mat ink;
  cv::transform(density, ink, cv::Matx13f(1, 1, 1));
  const cv::Rect box = cv::boundingRect(ink > 0.02f);
  EXPECT_GT(box.height, 2 * box.width) << box;
  EXPECT_GT(box.height, 20) << box;
}

TEST(WatercolorMarks, InsideAWashTouchesKeepItsValue) {
  std::vector<LeafPiece> leaves;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      leaves.push_back(leaf(
          {-1.2f + 0.2f * float(i), -1.2f + 0.2f * float(j), 0.01f * float(i % 3)}, 0.09f, 0.09f));
  const cv::Mat wash(kSize, kSize, CV_32FC3, cv::Scalar::all(1.5));
  cv::Mat density = wash.clone();
  glaze_marks(images_of(leaves, green()), params(), density);
  const cv::Rect inner(to_px({-0.8f, 0.8f, 0.0f}), to_px({0.8f, -0.8f, 0.0f}));
  cv::Scalar mean, sd;
  cv::meanStdDev(density(inner), mean, sd);
  EXPECT_NEAR(mean[0], 1.5, 0.1) << "the wash keeps its value";
  EXPECT_GT(sd[0] + sd[1] + sd[2], 0.03) << "and gains the leaves' texture";
}

TEST(WatercolorMarks, DarkLeavesCarryMoreOfTheirPigment) {
  // The left half of the plant dark, the right half light: per unit of its colour's density,
  // a dark leaf lays more pigment (denser touches in shadow).
  cv::Mat color = green(200);
  color(cv::Rect(0, 0, kSize / 2, kSize)).setTo(cv::Scalar(20, 40, 15, 255));
  const glm::vec3 dark{-1.0f, 0.0f, 0.0f}, light{1.0f, 0.0f, 0.0f};
  cv::Mat density(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(images_of({leaf(dark, 0.1f, 0.1f), leaf(light, 0.1f, 0.1f)}, color), params(),
              density);
  // -log2 of the linear transmittance of each colour's green channel.
  auto own = [](double srgb8) {
    const double c = srgb8 / 255.0;
    const double lin = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    return -std::log2(lin);
  };
  const double share_dark = density.at<cv::Vec3f>(to_px(dark))[1] / own(40);
  const double share_light = density.at<cv::Vec3f>(to_px(light))[1] / own(200);
  EXPECT_GT(share_dark, 1.5 * share_light) << share_dark << " " << share_light;
}

TEST(WatercolorMarks, TheSeenWoodStaysBareAndStrengthZeroIsNothing) {
  const LeafPiece l = leaf({0.0f, 0.0f, 0.0f}, 0.3f, 0.3f);
  WatercolorMarkImages in = images_of({l}, green());
  in.wood_cluster = 7;
  in.id(cv::Rect(to_px({-0.1f, 0.5f, 0.0f}), to_px({0.1f, -0.5f, 0.0f}))).setTo(7);
  cv::Mat density(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(in, params(), density);
  EXPECT_EQ(density_at(density, to_px({0.0f, 0.0f, 0.0f})), 0.0f) << "the trunk is bare";
  EXPECT_GT(density_at(density, to_px({0.2f, 0.0f, 0.0f})), 0.05f) << "the leaf beside it";
  cv::Mat again(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(in, params(), again);
  EXPECT_EQ(cv::norm(density, again, cv::NORM_INF), 0.0) << "deterministic";
  WatercolorMarkParams off = params();
  off.strength = 0.0f;
  cv::Mat none(kSize, kSize, CV_32FC3, cv::Scalar::all(0));
  glaze_marks(in, off, none);
  EXPECT_EQ(cv::countNonZero(none.reshape(1)), 0);
}

}  // namespace
}  // namespace sylva::test
