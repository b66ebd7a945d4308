// The AO study's options, CSV and chart without rendering (the study itself runs end to end
// in tests/cli/test_tradeoff.cpp): ranges name their option, rows count as documented, fields
// that do not apply are empty (never NaN), errors are quoted, and the chart draws with and
// without non-foliage pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "studies/ao_study.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

TEST(AoStudy, OptionsNameWhatIsWrong) {
  EXPECT_EQ(where_of([] { validate_ao_study({}); }), "no error");
  auto with = [](auto change) {
    return where_of([&] {
      AoStudyOptions o;
      change(o);
      validate_ao_study(o);
    });
  };
  EXPECT_EQ(with([](AoStudyOptions& o) { o.models = {}; }), "models");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.models = {"phong"}; }), "models");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.models = {"constant", "constant"}; }), "models");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.shells = {0}; }), "shells");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.shells = {65}; }), "shells");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.rays = {}; }), "rays");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.rays = {4097}; }), "rays");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.reference_rays = 0; }), "reference-rays");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.repeats = 101; }), "repeats");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.alpha_rho = "-1"; }), "ao.alpha_rho");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.alpha_rho = "nan"; }), "ao.alpha_rho");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.alpha_rho = "0.5"; }), "no error");
  EXPECT_EQ(with([](AoStudyOptions& o) { o.luft.grid = 1; }), "grid");
  // The Luft parameters only matter when luft-density is measured.
  EXPECT_EQ(with([](AoStudyOptions& o) {
              o.luft.grid = 1;
              o.models = {"constant"};
            }),
            "no error");
}

TEST(AoStudy, RunsCountTheRows) {
  AoStudyOptions o;  // every model, k = 1,2,4,8, rays 4,16,64, reference 256
  EXPECT_EQ(ao_study_runs(o), 2u + 4u + 4u + 3u);
  o.rays = {4, 256};  // the reference's ray count is its own row
  EXPECT_EQ(ao_study_runs(o), 2u + 4u + 4u + 1u);
  o.models = {"none"};
  EXPECT_EQ(ao_study_runs(o), 2u);
}

AoStudy synthetic_study(bool nonfoliage) {
  AoStudy s;
  s.width = s.height = 64;
  s.repeats = 3;
  s.reference_rays = 256;
  s.reference_mean = 0.55;
  AoStudyRow none;
  none.model = "none";
  none.setup_seconds = 0.0;
  none.frame_seconds = 0.01;
  none.added_seconds = 0.0;
  none.foliage = {100, 1.0, 0.5, 0.45, 0.4};
  none.nonfoliage.pixels = nonfoliage ? 10 : 0;
  if (nonfoliage) none.nonfoliage = {10, 1.0, 0.3, 0.3, 0.25};
  AoStudyRow failed;
  failed.model = "hegeman-sphere";
  failed.error = "ao.model: 'hegeman-sphere' needs foliage, \"really\"";
  failed.foliage.pixels = 100;
  AoStudyRow shells = none;
  shells.model = "hegeman-shells";
  shells.shells = 4;
  shells.alpha_rho = 12.5;
  shells.setup_seconds = 0.2;
  shells.frame_seconds = 0.012;
  shells.added_seconds = 0.002;
  shells.foliage = {100, 0.6, 0.2, 0.15, 0.1};
  AoStudyRow ref = none;
  ref.model = "raytraced";
  ref.rays = 256;
  ref.reference = true;
  ref.frame_seconds = 2.0;
  ref.added_seconds.reset();
  ref.foliage = {100, 0.55, 0.0, 0.0, 0.0};
  s.rows = {none, failed, shells, ref};
  return s;
}

TEST(AoStudy, CsvLeavesWhatDoesNotApplyEmpty) {
  const std::string csv = ao_study_csv(synthetic_study(false));
  EXPECT_EQ(count_lines(csv), 5);
  EXPECT_EQ(csv.rfind("model,shells,rays,reference,constant,alpha_rho,setup_seconds,", 0), 0u);
  EXPECT_NE(csv.find("\nnone,,,0,,,0.0000,0.01000,0.00000,100,1,0.5,0.45,0.4,0,,,,,\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\nhegeman-sphere,,,0,,,,,,100,,,,,0,,,,,\"ao.model: 'hegeman-sphere' "
                     "needs foliage, \"\"really\"\"\"\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\nhegeman-shells,4,,0,,12.5,0.2000,0.01200,0.00200,100,0.6,0.2,0.15,0.1,"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\nraytraced,,256,1,"), std::string::npos) << csv;
  // A non-finite number never reaches the CSV.
  AoStudy s = synthetic_study(true);
  s.rows[0].foliage.rmse = std::numeric_limits<double>::quiet_NaN();
  s.rows[0].foliage.trend_rmse = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ao_study_csv(s).find("nan"), std::string::npos);
  EXPECT_EQ(ao_study_csv(s).find("inf"), std::string::npos);
}

TEST(AoStudy, ChartDrawsWithAndWithoutNonFoliagePixels) {
  for (bool nonfoliage : {false, true}) {
    const cv::Mat img = plot_ao_study(synthetic_study(nonfoliage), "synthetic");
    ASSERT_EQ(img.type(), CV_8UC3);
    EXPECT_EQ(img.cols, 1200);
    EXPECT_EQ(img.rows, 800);
    cv::Mat grey;
    cv::extractChannel(img, grey, 0);
    EXPECT_GT(cv::countNonZero(grey < 250), 1000) << "something is drawn";
  }
  const cv::Mat small = plot_ao_study(synthetic_study(true), "synthetic", 600, 400);
  EXPECT_EQ(small.cols, 600);
  EXPECT_EQ(small.rows, 400);
}

}  // namespace
}  // namespace sylva::test
