// watercolor.mass through `sylva` on a shared tree: the crown painted as a few masses has
// fewer thin dark rims inside it than one wash per leaf cluster (the measure of
// ../shared/tools/depiction.py: a pixel 8 levels darker than its surroundings blurred by 4 px at
// 1024 px), and the picture is the same bytes on a second render; a mass is not cut off by the
// box it is painted in; a fern is painted frond by frond; a willow's curtain is a pale veil.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

constexpr int kSize = 384;

cv::Mat render_mass(const std::string& mass, const std::string& out) {
  const RunResult r = run_sylva("render " + shared_dir() + "/assets/eztree_ash_medium_s5.glb" +
                                " --style watercolor --size " + std::to_string(kSize) +
                                " --set watercolor.mass=" + mass + " -o " + out);
  EXPECT_EQ(r.status, 0) << r.output;
  return cv::imread(out, cv::IMREAD_COLOR);
}

// Share of the crown's interior (the painted pixels, closed and eroded by 3 % of the size)
// that is a thin dark rim.
double rim_share(const cv::Mat& picture, const cv::Mat& paper) {
  cv::Mat grey, blurred, diff;
  cv::cvtColor(picture, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  const double s = kSize / 1024.0;
  cv::GaussianBlur(grey, blurred, {0, 0}, 4.0 * s);
  const cv::Mat rim = (grey - blurred) < -8.0f;
  cv::absdiff(picture, paper, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::Mat plant = diff > 24;
  auto disc = [](double r) {
    const int k = 2 * std::max(1, int(r)) + 1;
    return cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
  };
  cv::morphologyEx(plant, plant, cv::MORPH_CLOSE, disc(0.01 * kSize));
  cv::erode(plant, plant, disc(0.03 * kSize));
  const double n = cv::countNonZero(plant);
  return n > 0 ? cv::countNonZero(rim & plant) / n : 0.0;
}

TEST(WatercolorCli, MassesPaintFewerRimsThanOneWashPerCluster) {
  const std::string dir = temp_dir("watercolor-mass");
  const cv::Mat clusters = render_mass("0", dir + "/clusters.png");
  const cv::Mat masses = render_mass("450", dir + "/masses.png");
  ASSERT_FALSE(clusters.empty() || masses.empty());
  const cv::Mat paper(clusters.size(), CV_8UC3, clusters.at<cv::Vec3b>(2, 2));
  const double before = rim_share(clusters, paper), after = rim_share(masses, paper);
  EXPECT_GT(before, 0.05);
  EXPECT_LT(after, 0.85 * before) << "rims " << before << " -> " << after;
  const cv::Mat again = render_mass("450", dir + "/again.png");
  EXPECT_EQ(cv::norm(masses, again, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace sylva::test

namespace sylva::test {
namespace {

// The mean colour of the painted pixels (those differing from the paper in the corner).
cv::Scalar painted_mean(const cv::Mat& picture) {
  const cv::Mat paper(picture.size(), CV_8UC3, picture.at<cv::Vec3b>(2, 2));
  cv::Mat diff;
  cv::absdiff(picture, paper, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  return cv::mean(picture, diff > 24);
}

TEST(WatercolorCli, SupersamplingKeepsThePigment) {
  // With --ssaa the colour's edge samples are averaged with what lies around the leaves: the
  // washes must still take the leaves' colour (premultiplied over a transparent black clear),
  // not the background's white mixed in, which greyed every wash of a sparse crown. In a stack
  // (pen-and-wash) the colour is cleared to the line layer's transparent white, which the wash
  // takes out again (old binary: mean BGR 77/100/88 at --ssaa 1 against 113/124/121 at 2).
  const std::string dir = temp_dir("watercolor-ssaa");
  for (const std::string style : {"watercolor", "pen-and-wash"}) {
    cv::Scalar mean[2];
    for (int k = 0; k < 2; ++k) {
      const std::string out = dir + "/" + style + std::to_string(k + 1) + ".png";
      const RunResult r =
          run_sylva("render " + shared_dir() + "/assets/eztree_ash_medium_s5.glb" + " --style " +
                    style + " --size 192 --ssaa " + std::to_string(k + 1) + " -o " + out);
      ASSERT_EQ(r.status, 0) << r.output;
      mean[k] = painted_mean(cv::imread(out, cv::IMREAD_COLOR));
    }
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(mean[1][c], mean[0][c], 12.0)
          << style << " channel " << c << ": " << mean[0] << " vs " << mean[1];
  }
}

// The longest straight run (px) of a paint-paper boundary along a row or a column: a wash's
// edge wobbles along the paper, so a long straight one is a wash cut off by the box it was
// painted in.
int longest_straight_edge(const cv::Mat& picture) {
  cv::Mat diff;
  const cv::Mat paper(picture.size(), CV_8UC3, picture.at<cv::Vec3b>(2, 2));
  cv::absdiff(picture, paper, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  const cv::Mat painted = diff > 12;
  int longest = 0;
  for (const cv::Mat& m : {painted, cv::Mat(painted.t())})
    for (int y = 1; y < m.rows; ++y) {
      int run = 0;
      for (int x = 0; x < m.cols; ++x) {
        const bool edge = (m.at<uint8_t>(y, x) != 0) != (m.at<uint8_t>(y - 1, x) != 0);
        run = edge ? run + 1 : 0;
        longest = std::max(longest, run);
      }
    }
  return longest;
}

TEST(WatercolorCli, AMassIsNotCutOffByItsBox) {
  // A mass's gaps are closed over a radius (a twentieth of watercolor.mass) that can exceed the
  // padding of the box its wash is painted in. The closing kept its dilation along the box's
  // edge, so the wash ended there in a straight line (with that closing: a 104 px straight edge
  // on the ash at 512 px with watercolor.mass = 900, and cuts in the default ash at 2048 px).
  const std::string out = temp_dir("watercolor-cut") + "/ash.png";
  const RunResult r =
      run_sylva("render " + shared_dir() + "/assets/eztree_ash_medium_s5.glb" +
                " --style watercolor --size 512 --set watercolor.mass=900 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_LT(longest_straight_edge(cv::imread(out, cv::IMREAD_COLOR)), 40);
}

// A disc of radius r px (rounded, at least 1) for the morphology below.
cv::Mat disc(double r) {
  const int k = 2 * std::max(1, int(std::lround(r))) + 1;
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k});
}

// The plant: the standard render's alpha (CV_8UC1, 255 = plant).
cv::Mat plant_of(const cv::Mat& standard) {
  cv::Mat plant;
  cv::extractChannel(standard, plant, 3);
  return plant > 0;
}

// The share of the plant's area (the standard render's alpha) that the picture paints beyond
// the plant closed and grown by 1 % of the size (../shared/tools/depiction.py's overreach).
double overreach(const cv::Mat& standard, const cv::Mat& picture) {
  const int size = picture.cols;
  const cv::Mat plant = plant_of(standard);
  cv::Mat grown, painted;
  cv::morphologyEx(plant, grown, cv::MORPH_CLOSE, disc(0.01 * size));
  cv::dilate(grown, grown, disc(0.01 * size));
  const cv::Mat paper(picture.size(), CV_8UC3, picture.at<cv::Vec3b>(2, 2));
  cv::absdiff(picture, paper, painted);
  cv::cvtColor(painted, painted, cv::COLOR_BGR2GRAY);
  cv::morphologyEx(painted > 12, painted, cv::MORPH_OPEN, disc(2.0 * size / 1024.0));
  return double(cv::countNonZero(painted & ~grown)) / std::max(1, cv::countNonZero(plant));
}

TEST(WatercolorCli, AFernIsPaintedFrondByFrond) {
  // The fern's fronds span a sixth of its foliage (passes/watercolor_masses.h kLargeLeaf): its
  // masses close no gaps and its parts are smoothed less, so the paper between its fronds stays
  // bare. Painted as a tree's masses, each plant was one patch over its fronds and the paper
  // between them (0.028 of the plant's area beyond it at 384 px).
  const std::string dir = temp_dir("watercolor-fern");
  const std::string fern = shared_dir() + "/assets/polyhaven_fern_02.glb";
  // The standard render's alpha is the plant.
  for (const std::string style : {"standard --background transparent", "watercolor"}) {
    const std::string name = style.substr(0, style.find(' '));
    const RunResult r = run_sylva("render " + fern + " --style " + style + " --size 384 -o " + dir +
                                  "/" + name + ".png");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const cv::Mat standard = cv::imread(dir + "/standard.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(standard.channels(), 4);
  EXPECT_LT(overreach(standard, cv::imread(dir + "/watercolor.png", cv::IMREAD_COLOR)), 0.01);
}

// The share of the plant's interior (the standard render's alpha closed by 1 % of the size and
// eroded by 3 %) that is a thin dark rim: ../shared/tools/depiction.py's rims.
double interior_rims(const cv::Mat& standard, const cv::Mat& picture) {
  const int size = picture.cols;
  cv::Mat plant, grey, blurred;
  cv::morphologyEx(plant_of(standard), plant, cv::MORPH_CLOSE, disc(0.01 * size));
  cv::erode(plant, plant, disc(0.03 * size));
  cv::cvtColor(picture, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey, CV_32F);
  cv::GaussianBlur(grey, blurred, {0, 0}, 4.0 * size / 1024.0);
  const cv::Mat rim = (grey - blurred) < -8.0f;
  return double(cv::countNonZero(rim & plant)) / std::max(1, cv::countNonZero(plant));
}

TEST(WatercolorCli, AWillowsCurtainIsAPaleVeilNotAQuiltOfRims) {
  // A wash thins where the foliage thins (passes/watercolor_layers.h kThinCover): the willow's
  // curtain of hanging strands is one pale veil over the paper, not masses with paper holes
  // and a hard, dark-rimmed edge around each. With full washes ending at the crown's parts the
  // willow's interior was 0.16 rim at 384 px.
  const std::string dir = temp_dir("watercolor-willow");
  const std::string willow = shared_dir() + "/assets/sapling_weeping_willow_s2.glb";
  for (const std::string style : {"standard --background transparent", "watercolor"}) {
    const std::string name = style.substr(0, style.find(' '));
    const RunResult r = run_sylva("render " + willow + " --style " + style + " --size 384 -o " +
                                  dir + "/" + name + ".png");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const cv::Mat standard = cv::imread(dir + "/standard.png", cv::IMREAD_UNCHANGED);
  const cv::Mat painted = cv::imread(dir + "/watercolor.png", cv::IMREAD_COLOR);
  ASSERT_EQ(standard.channels(), 4);
  EXPECT_LT(interior_rims(standard, painted), 0.12);
  EXPECT_LT(overreach(standard, painted), 0.02);
}

}  // namespace
}  // namespace sylva::test
