// The foliage speed/accuracy study (studies/foliage_study.h) on a small sample tree: the
// reference's own row has zero error, errors are finite and >= 0, fewer generators on a
// coarser grid are worse, the attribute encoding is at least as exact inside triangles as
// the length encoding, failed runs are recorded, determinism, option ranges, CSV and chart.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "samples/plants.h"
#include "studies/foliage_study.h"

namespace sylva {
namespace {

const Scene& tree() {
  static const Scene s = [] {
    PlantOptions o;
    o.leaves = 2500;
    o.seed = 2;
    return make_plant(o);
  }();
  return s;
}

// fractions {1, 0.05} x grids {32, 256} x both sources x both encodings, computed once.
const FoliageStudy& study() {
  static const FoliageStudy s = [] {
    FoliageStudyOptions o;
    o.fractions = {1, 0.05};
    o.grids = {32, 256};
    return run_foliage_study(tree(), o);
  }();
  return s;
}

const FoliageStudyRow& row(const FoliageStudy& s, double fraction, int grid, NormalSource n,
                           KaEncoding e) {
  for (const FoliageStudyRow& r : s.rows)
    if (r.fraction == fraction && r.grid == grid && r.normals == n && r.encoding == e) return r;
  ADD_FAILURE() << "no row " << fraction << " " << grid;
  return s.rows.front();
}

TEST(FoliageStudy, RowsInSweepOrder) {
  const FoliageStudy& s = study();
  ASSERT_EQ(s.rows.size(), 16u);
  EXPECT_EQ(s.reference_grid, 256);
  EXPECT_EQ(s.reference.generators, 2500u);
  EXPECT_EQ(s.rows[0].fraction, 1.0);
  EXPECT_EQ(s.rows[0].grid, 32);
  EXPECT_EQ(s.rows[0].normals, NormalSource::Surface);
  EXPECT_EQ(s.rows[0].encoding, KaEncoding::Length);
  EXPECT_EQ(s.rows[1].encoding, KaEncoding::Attribute);
  EXPECT_EQ(s.rows[2].normals, NormalSource::Gradient);
  EXPECT_EQ(s.rows[15].fraction, 0.05);
  EXPECT_EQ(s.rows[15].grid, 256);
  int references = 0;
  for (const FoliageStudyRow& r : s.rows)
    references += r.reference;
  EXPECT_EQ(references, 2);  // one per encoding
  EXPECT_EQ(*row(s, 0.05, 32, NormalSource::Surface, KaEncoding::Length).generators, 125u);
}

TEST(FoliageStudy, ReferenceRowHasZeroError) {
  const FoliageStudyRow& a = row(study(), 1.0, 256, NormalSource::Surface, KaEncoding::Attribute);
  EXPECT_TRUE(a.reference);
  EXPECT_TRUE(a.error.empty()) << a.error;
  EXPECT_EQ(*a.normal_mean_deg, 0.0);
  EXPECT_EQ(*a.normal_p95_deg, 0.0);
  EXPECT_EQ(*a.ka_rmse, 0.0);
  EXPECT_EQ(*a.ka_interior_rmse, 0.0);
  // The length encoding's run is the same; only the decoding inside triangles differs
  // (Luft §3.2: |interpolated N| <= interpolated ka).
  const FoliageStudyRow& l = row(study(), 1.0, 256, NormalSource::Surface, KaEncoding::Length);
  EXPECT_EQ(*l.normal_mean_deg, 0.0);
  EXPECT_EQ(*l.ka_rmse, 0.0);
  EXPECT_GT(*l.ka_interior_rmse, 0.0);
}

TEST(FoliageStudy, ErrorsFiniteAndNonNegative) {
  for (const FoliageStudyRow& r : study().rows) {
    ASSERT_TRUE(r.error.empty()) << r.error;
    for (const std::optional<double>& v :
         {r.seconds, r.normal_mean_deg, r.normal_p95_deg, r.ka_rmse, r.ka_interior_rmse}) {
      ASSERT_TRUE(v.has_value());
      EXPECT_TRUE(std::isfinite(*v));
      EXPECT_GE(*v, 0.0);
    }
    EXPECT_LE(*r.normal_mean_deg, 180.0);
    EXPECT_LE(*r.normal_p95_deg, 180.0);
    EXPECT_GE(*r.normal_p95_deg, 0.0);
    EXPECT_LE(*r.ka_rmse, 1.0);
    EXPECT_LE(*r.ka_interior_rmse, 1.0);
  }
}

TEST(FoliageStudy, FewerGeneratorsOnACoarserGridAreWorse) {
  for (NormalSource n : {NormalSource::Surface, NormalSource::Gradient}) {
    const FoliageStudyRow& coarse = row(study(), 0.05, 32, n, KaEncoding::Attribute);
    const FoliageStudyRow& fine = row(study(), 1.0, 256, n, KaEncoding::Attribute);
    EXPECT_GT(*coarse.normal_mean_deg, *fine.normal_mean_deg) << normal_source_name(n);
    EXPECT_GT(*coarse.ka_rmse, *fine.ka_rmse) << normal_source_name(n);
  }
}

TEST(FoliageStudy, AttributeEncodingIsAtLeastAsExactInside) {
  const FoliageStudy& s = study();
  for (size_t i = 0; i + 1 < s.rows.size(); i += 2) {
    const FoliageStudyRow& length = s.rows[i];
    const FoliageStudyRow& attribute = s.rows[i + 1];
    ASSERT_EQ(length.encoding, KaEncoding::Length);
    ASSERT_EQ(attribute.encoding, KaEncoding::Attribute);
    EXPECT_LE(*attribute.ka_interior_rmse, *length.ka_interior_rmse)
        << "fraction " << length.fraction << " grid " << length.grid << " "
        << normal_source_name(length.normals);
    // The encoding changes nothing but the decoding.
    EXPECT_EQ(*attribute.normal_mean_deg, *length.normal_mean_deg);
    EXPECT_EQ(*attribute.ka_rmse, *length.ka_rmse);
    EXPECT_EQ(*attribute.seconds, *length.seconds);
  }
}

// Same rows apart from the times; a run that fails (no grid node inside the surface at 2
// cells) is recorded with its reason and empty numbers, and the study goes on.
TEST(FoliageStudy, DeterministicAndFailuresRecorded) {
  FoliageStudyOptions o;
  o.fractions = {0.5, 0.001};
  o.grids = {2, 24};
  o.reference_grid = 48;
  o.encodings = {KaEncoding::Attribute};
  std::vector<std::string> runs;
  o.on_run = [&](const std::string& what) { runs.push_back(what); };
  const FoliageStudy a = run_foliage_study(tree(), o);
  const FoliageStudy b = run_foliage_study(tree(), o);
  EXPECT_EQ(runs.size(), 2 * foliage_study_runs(o));
  EXPECT_EQ(foliage_study_runs(o), 9u);
  EXPECT_EQ(runs.front(), "reference: fraction 1, grid 48, surface");
  ASSERT_EQ(a.rows.size(), 8u);
  ASSERT_EQ(b.rows.size(), a.rows.size());
  size_t failed = 0;
  for (size_t i = 0; i < a.rows.size(); ++i) {
    const FoliageStudyRow &x = a.rows[i], &y = b.rows[i];
    EXPECT_EQ(x.error, y.error);
    EXPECT_EQ(x.generators, y.generators);
    EXPECT_EQ(x.normal_mean_deg, y.normal_mean_deg);
    EXPECT_EQ(x.normal_p95_deg, y.normal_p95_deg);
    EXPECT_EQ(x.ka_rmse, y.ka_rmse);
    EXPECT_EQ(x.ka_interior_rmse, y.ka_interior_rmse);
    if (!x.error.empty()) {
      ++failed;
      EXPECT_FALSE(x.seconds || x.generators || x.normal_mean_deg || x.ka_rmse ||
                   x.ka_interior_rmse);
    } else {
      EXPECT_TRUE(x.seconds && x.normal_mean_deg && x.ka_interior_rmse);
    }
  }
  EXPECT_GE(failed, 1u);
  const std::string csv = foliage_study_csv(a);
  ASSERT_TRUE(a.rows[6].generators.has_value()) << csv;
  EXPECT_EQ(*a.rows[6].generators, 3u);  // fraction 0.001 of 2500 leaves: 2.5, rounded
  EXPECT_EQ(csv, foliage_study_csv(a));
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  EXPECT_NE(csv.find(",\"grid: "), std::string::npos) << csv;
}

// With fewer generators the density sums fewer kernels: thresholds scaled by the share of
// generators keep the surface and ka close to the reference; the reference's own are far off.
TEST(FoliageStudy, ScaledThresholdsFollowTheFraction) {
  FoliageStudyOptions o;
  o.fractions = {0.25};
  o.grids = {32};
  o.reference_grid = 64;
  o.normals = {NormalSource::Surface};
  o.encodings = {KaEncoding::Attribute};
  const FoliageStudy scaled = run_foliage_study(tree(), o);
  o.scale_thresholds = false;
  const FoliageStudy fixed = run_foliage_study(tree(), o);
  ASSERT_EQ(scaled.rows.size(), 1u);
  ASSERT_EQ(fixed.rows.size(), 1u);
  const FoliageStudyRow &s = scaled.rows[0], &f = fixed.rows[0];
  const double share = double(*s.generators) / double(scaled.reference.generators);
  EXPECT_NEAR(share, 0.25, 0.01);
  EXPECT_FLOAT_EQ(float(s.tau), float(scaled.reference.tau * share));
  EXPECT_FLOAT_EQ(float(s.d_min), float(scaled.reference.d_min * share));
  EXPECT_FLOAT_EQ(float(f.tau), float(fixed.reference.tau));
  EXPECT_FLOAT_EQ(float(f.d_min), float(fixed.reference.d_min));
  EXPECT_LT(*s.ka_rmse, *f.ka_rmse);
  EXPECT_LT(*s.normal_mean_deg, *f.normal_mean_deg);
}

TEST(FoliageStudy, Csv) {
  const std::string csv = foliage_study_csv(study());
  EXPECT_EQ(csv.rfind("fraction,grid,normals,encoding,reference,generators,tau,d_min,seconds,"
                      "normal_mean_deg,normal_p95_deg,ka_rmse,ka_interior_rmse,error\n",
                      0),
            0u);
  size_t lines = 0;
  for (char c : csv)
    lines += c == '\n';
  EXPECT_EQ(lines, 17u);
  EXPECT_NE(csv.find("\n1,256,surface,attribute,1,2500,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n0.05,32,gradient,length,0,125,"), std::string::npos) << csv;
}

TEST(FoliageStudy, ChartIsDrawn) {
  const cv::Mat img = plot_foliage_study(study(), "tree");
  ASSERT_EQ(img.type(), CV_8UC3);
  EXPECT_EQ(img.cols, 1200);
  EXPECT_EQ(img.rows, 800);
  // Mostly white, with ink in both panels.
  cv::Mat grey;
  cv::extractChannel(img, grey, 1);
  const double white = double(cv::countNonZero(grey == 255)) / double(img.total());
  EXPECT_GT(white, 0.7);
  EXPECT_LT(white, 0.99);
  EXPECT_GT(cv::countNonZero(grey(cv::Rect(100, 150, 450, 400)) < 200), 500);
  EXPECT_GT(cv::countNonZero(grey(cv::Rect(700, 150, 450, 400)) < 200), 500);
}

TEST(FoliageStudy, OptionRanges) {
  FoliageStudyOptions o;
  auto expect_error = [&](const char* where) {
    try {
      validate_foliage_study(o);
      ADD_FAILURE() << "no error for " << where;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), where) << e.what();
    }
    o = FoliageStudyOptions{};
  };
  EXPECT_NO_THROW(validate_foliage_study(o));
  o.fractions = {0.5, 0.0};
  expect_error("fractions");
  o.fractions = {1.5};
  expect_error("fractions");
  o.fractions = {std::nan("")};
  expect_error("fractions");
  o.fractions = {};
  expect_error("fractions");
  o.grids = {1};
  expect_error("grids");
  o.grids = {1025};
  expect_error("grids");
  o.normals = {};
  expect_error("normal-sources");
  o.encodings = {};
  expect_error("encodings");
  o.reference_grid = 1;
  expect_error("reference-grid");
  o.base.ambient.ka_min = 2.0f;
  expect_error("ka-min");
  o.fractions = {1e-9, 1.0};
  o.grids = {2, 1024};
  EXPECT_NO_THROW(validate_foliage_study(o));
}

}  // namespace
}  // namespace sylva
