// sylva tradeoff: a quick foliage sweep writes the CSV (header, one row per run and
// encoding) and a PNG chart that decodes, with a progress line per run on a pipe; the AO
// study writes one row per model with errors that order as they should (more rays, less
// error; fitted Hegeman sphere better than the best constant on the foliage); the keyframes
// study writes one row per interval, n = 1 being the reference; bad studies and out-of-range
// lists exit 2 with one line and write nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

TEST(Tradeoff, QuickFoliageSweep) {
  const std::string dir = temp_dir("tradeoff");
  const RunResult r = run_sylva("tradeoff " + small_tree() +
                                " --study foliage --fractions 1,0.25 --grids 16,32 -o " + dir +
                                "/study.csv --plot " + dir + "/study.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = read_file(dir + "/study.csv");
  EXPECT_EQ(csv.rfind("fraction,grid,normals,encoding,reference,generators,tau,d_min,seconds,"
                      "normal_mean_deg,normal_p95_deg,ka_rmse,ka_interior_rmse,error\n",
                      0),
            0u)
      << csv;
  EXPECT_EQ(count_lines(csv), 1 + 2 * 2 * 2 * 2) << csv;  // fractions x grids x sources x enc.
  EXPECT_EQ(csv.find("nan"), std::string::npos);
  const cv::Mat plot = cv::imread(dir + "/study.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.cols, 1200);
  EXPECT_EQ(plot.rows, 800);
  // Progress on a pipe: one plain line per run (the reference and 8 sweep runs), no '\r'.
  EXPECT_NE(r.output.find("foliage study 9/9  100%"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find('\r'), std::string::npos);
  EXPECT_NE(r.output.find("ka_int_attribute"), std::string::npos) << r.output;
  for (const auto& e : fs::directory_iterator(dir))  // no temporary files left
    EXPECT_TRUE(e.path().filename() == "study.csv" || e.path().filename() == "study.png")
        << e.path();
}

// The sweep starts from a style's foliage settings: --set foliage.tau fixes the threshold of
// the reference and of the full-generator run.
TEST(Tradeoff, SetChoosesTheBaseSettings) {
  const std::string dir = temp_dir("tradeoff-set");
  const RunResult r = run_sylva("tradeoff " + small_tree() +
                                " --study foliage --fractions 1 --grids 16 --normal-sources "
                                "surface --encodings attribute --set foliage.tau=3 -q -o " +
                                dir + "/s.csv");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = read_file(dir + "/s.csv");
  const std::string row = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(row.rfind("1,16,surface,attribute,", 0), 0u) << csv;
  EXPECT_NE(row.find(",3,"), std::string::npos) << csv;  // the tau column
}

const std::map<std::string, std::string>* find_row(
    const std::vector<std::map<std::string, std::string>>& rows, const std::string& model,
    const std::string& column = "", const std::string& value = "") {
  for (const auto& r : rows)
    if (r.at("model") == model && (column.empty() || r.at(column) == value)) return &r;
  return nullptr;
}

const char* const kAoHeader =
    "model,shells,rays,reference,constant,alpha_rho,setup_seconds,frame_seconds,added_seconds,"
    "foliage_pixels,foliage_mean,foliage_rmse,foliage_mae,foliage_trend_rmse,nonfoliage_pixels,"
    "nonfoliage_mean,nonfoliage_rmse,nonfoliage_mae,nonfoliage_trend_rmse,error\n";

// Every model on the small sample tree: the rows and columns, no NaN, and the orderings the
// issue asks for, against the ray-traced reference with 256 rays.
TEST(Tradeoff, AoStudyOnTheSampleTree) {
  const std::string dir = temp_dir("tradeoff-ao");
  const RunResult r =
      run_sylva("tradeoff " + small_tree() + " --study ao --size 96x96 --repeats 1 -o " + dir +
                "/ao.csv --plot " + dir + "/ao.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = read_file(dir + "/ao.csv");
  ASSERT_EQ(csv.rfind(kAoHeader, 0), 0u) << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("inf"), std::string::npos) << csv;
  const auto rows = parse_csv(csv);
  // none, constant, luft-density, sphere, ellipsoid, 4 shell counts, 3 ray counts, reference
  ASSERT_EQ(rows.size(), 13u) << csv;
  std::vector<std::string> order;
  for (const auto& row : rows) {
    order.push_back(row.at("model") + row.at("shells") + row.at("rays"));
    EXPECT_EQ(row.at("error"), "") << csv;
    EXPECT_GT(number(row, "foliage_pixels"), 100) << csv;
    EXPECT_GT(number(row, "nonfoliage_pixels"), 0) << csv;  // the trunk
    for (const char* c : {"foliage_mean", "foliage_rmse", "foliage_mae", "nonfoliage_rmse"}) {
      const double v = number(row, c);
      EXPECT_TRUE(v >= 0.0 && v <= 1.0) << c << " " << v;
    }
    EXPECT_LE(number(row, "foliage_mae"), number(row, "foliage_rmse") + 1e-9);
    EXPECT_GT(number(row, "frame_seconds"), 0.0);
  }
  EXPECT_EQ(order, (std::vector<std::string>{
                       "none", "constant", "luft-density", "hegeman-sphere", "hegeman-ellipsoid",
                       "hegeman-shells1", "hegeman-shells2", "hegeman-shells4", "hegeman-shells8",
                       "raytraced4", "raytraced16", "raytraced64", "raytraced256"}));
  const auto* reference = find_row(rows, "raytraced", "reference", "1");
  ASSERT_TRUE(reference);
  EXPECT_EQ(reference->at("rays"), "256");
  EXPECT_EQ(number(*reference, "foliage_rmse"), 0.0);
  // constant is the reference's mean over every evaluated pixel.
  const auto* constant = find_row(rows, "constant");
  const double fp = number(*reference, "foliage_pixels"),
               np = number(*reference, "nonfoliage_pixels");
  EXPECT_NEAR(
      number(*constant, "constant"),
      (number(*reference, "foliage_mean") * fp + number(*reference, "nonfoliage_mean") * np) /
          (fp + np),
      1e-4);
  // More rays, less error.
  EXPECT_GT(number(*find_row(rows, "raytraced", "rays", "4"), "foliage_rmse"),
            number(*find_row(rows, "raytraced", "rays", "64"), "foliage_rmse"));
  EXPECT_GT(number(*find_row(rows, "raytraced", "rays", "4"), "nonfoliage_rmse"),
            number(*find_row(rows, "raytraced", "rays", "64"), "nonfoliage_rmse"));
  // With alpha_rho fitted (each traced leaf face weighted by its visibility), Hegeman's
  // models darken the visible leaves as much as the reference does on average (unweighted,
  // the sphere's mean was 0.27 against 0.45), and the ellipsoid beats the best constant on
  // this tree's leaves: RMSE 0.200 against 0.211 (on the 10,000-leaf default tree the two
  // tie, and on the shared fern constant wins; README, "AO study"). On the trunk the crown's
  // solid angle (Eq. 7-8) beats it too: 0.24 against 0.33.
  const auto* sphere = find_row(rows, "hegeman-sphere");
  const auto* ellipsoid = find_row(rows, "hegeman-ellipsoid");
  for (const auto* row : {sphere, ellipsoid}) {
    EXPECT_GT(number(*row, "alpha_rho"), 0.0);
    EXPECT_NEAR(number(*row, "foliage_mean"), number(*reference, "foliage_mean"), 0.05) << csv;
  }
  EXPECT_LT(number(*sphere, "foliage_rmse"), 0.6 * number(*find_row(rows, "none"), "foliage_rmse"))
      << csv;
  EXPECT_LT(number(*ellipsoid, "foliage_rmse"), number(*constant, "foliage_rmse")) << csv;
  EXPECT_LT(number(*sphere, "nonfoliage_rmse"), 0.85 * number(*constant, "nonfoliage_rmse")) << csv;
  // At the crown's scale the leaf-to-leaf scatter is gone: constant's trend error is well
  // below its per-pixel error, and the reference's is 0.
  EXPECT_EQ(number(*reference, "foliage_trend_rmse"), 0.0);
  EXPECT_LT(number(*constant, "foliage_trend_rmse"), 0.7 * number(*constant, "foliage_rmse"));
  for (const auto& row : rows)
    for (const char* c : {"foliage_trend_rmse", "nonfoliage_trend_rmse"}) {
      const double v = number(row, c);
      EXPECT_TRUE(v >= 0.0 && v <= 1.0) << c << " " << v;
    }
  // The AO buffer of none is 1 everywhere.
  EXPECT_EQ(number(*find_row(rows, "none"), "foliage_mean"), 1.0);

  const cv::Mat plot = cv::imread(dir + "/ao.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.cols, 1200);
  EXPECT_EQ(plot.rows, 800);
  EXPECT_NE(r.output.find("ao study 13/13  100%"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("hegeman-shells"), std::string::npos) << r.output;
  for (const auto& e : fs::directory_iterator(dir))  // no temporary files left
    EXPECT_TRUE(e.path().filename() == "ao.csv" || e.path().filename() == "ao.png") << e.path();
}

// The same inputs give the same errors (only the times differ); with no foliage the models
// that need it keep their rows with the reason, and the foliage columns are empty, not NaN.
TEST(Tradeoff, AoStudyIsDeterministicAndKeepsFailedRows) {
  const std::string dir = temp_dir("tradeoff-ao-det");
  const std::string args = "tradeoff " + small_tree() +
                           " --study ao --size 48x48 --repeats 1 --models "
                           "constant,hegeman-sphere,luft-density,raytraced --rays 4 "
                           "--reference-rays 32 -q --seed 5 -o " +
                           dir;
  auto errors_only = [](const std::string& csv) {
    std::string out;
    for (const auto& row : parse_csv(csv))
      for (const auto& [k, v] : row)
        if (k.find("seconds") == std::string::npos) out += k + "=" + v + ";";
    return out;
  };
  RunResult r = run_sylva(args + "/a.csv");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run_sylva(args + "/b.csv");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("ao study"), std::string::npos) << "-q prints no progress";
  const std::string a = read_file(dir + "/a.csv");
  EXPECT_EQ(errors_only(a), errors_only(read_file(dir + "/b.csv")));
  EXPECT_EQ(count_lines(a), 1 + 6);  // none, constant, luft, sphere, raytraced 4, reference

  r = run_sylva(args + "/c.csv --foliage none");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string c = read_file(dir + "/c.csv");
  EXPECT_EQ(c.find("nan"), std::string::npos) << c;
  const auto rows = parse_csv(c);
  ASSERT_EQ(rows.size(), 6u) << c;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("foliage_pixels"), "0") << c;
    EXPECT_EQ(row.at("foliage_rmse"), "") << c;
    EXPECT_EQ(row.at("foliage_mae"), "") << c;
    const bool needs_foliage =
        row.at("model") == "hegeman-sphere" || row.at("model") == "luft-density";
    EXPECT_EQ(row.at("error").empty(), !needs_foliage) << c;
    EXPECT_EQ(row.at("nonfoliage_rmse").empty(), needs_foliage) << c;
  }
}

// A tiny blobs turntable: one row per interval, n = 1 is the reference (no difference from
// itself, a keyframe per frame), a larger interval shrink-wraps fewer keyframes, no NaN.
TEST(Tradeoff, KeyframeStudyOnTheSampleTree) {
  const std::string dir = temp_dir("tradeoff-kf");
  const RunResult r =
      run_sylva("tradeoff " + small_tree() + " --study keyframes --size 64 --frames 8 --every " +
                "1,4 -o " + dir + "/kf.csv --plot " + dir + "/kf.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = read_file(dir + "/kf.csv");
  ASSERT_EQ(csv.rfind("every,reference,frames,seconds,seconds_per_frame,keyframes,flicker_mean,"
                      "flicker_max,jitter_mean,error_mean,error_max\n",
                      0),
            0u)
      << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("inf"), std::string::npos) << csv;
  const auto rows = parse_csv(csv);
  ASSERT_EQ(rows.size(), 2u) << csv;
  const auto& ref = rows[0];
  const auto& kf = rows[1];
  EXPECT_EQ(ref.at("every"), "1");
  EXPECT_EQ(ref.at("reference"), "1");
  EXPECT_EQ(number(ref, "keyframes"), 8);
  EXPECT_EQ(number(ref, "error_mean"), 0);
  EXPECT_EQ(number(ref, "error_max"), 0);
  EXPECT_EQ(kf.at("every"), "4");
  EXPECT_EQ(kf.at("reference"), "0");
  EXPECT_LT(number(kf, "keyframes"), number(ref, "keyframes"));
  EXPECT_GE(number(kf, "keyframes"), 2);
  for (const auto& row : rows) {
    EXPECT_EQ(number(row, "frames"), 8);
    EXPECT_GT(number(row, "seconds"), 0);
    EXPECT_GT(number(row, "flicker_mean"), 0);  // the plant turns
    EXPECT_GE(number(row, "flicker_max"), number(row, "flicker_mean"));
    EXPECT_GE(number(row, "jitter_mean"), 0);
    EXPECT_GE(number(row, "error_max"), number(row, "error_mean"));
  }
  const cv::Mat plot = cv::imread(dir + "/kf.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.cols, 1200);
  EXPECT_NE(r.output.find("keyframes study 16/16  100%"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(reference)"), std::string::npos) << r.output;
}

// The coherence study: every style named, a row each with the motion taken out; the line
// styles have a line pop, the others none; the reprojection error is under the plain flicker.
TEST(Tradeoff, CoherenceStudyOnTheSampleTree) {
  const std::string dir = temp_dir("tradeoff-coherence");
  const RunResult r =
      run_sylva("tradeoff " + small_tree() +
                " --study coherence --styles standard,ink,pen --size 96 --frames 4 " +
                "--step 2 -o " + dir + "/c.csv --plot " + dir + "/c.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = read_file(dir + "/c.csv");
  ASSERT_EQ(csv.rfind("style,frames,step_deg,width,height,seconds_per_frame,"
                      "reprojection_error_mean,reprojection_error_max,line_pop_mean,line_pop_max,"
                      "flicker_mean\n",
                      0),
            0u)
      << csv;
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  const auto rows = parse_csv(csv);
  ASSERT_EQ(rows.size(), 3u) << csv;
  EXPECT_EQ(rows[0].at("style"), "standard");
  EXPECT_EQ(rows[0].at("line_pop_mean"), "");
  for (size_t i = 1; i < 3; ++i) {
    EXPECT_GE(number(rows[i], "line_pop_mean"), 0.0);
    EXPECT_LE(number(rows[i], "line_pop_max"), 1.0);
    EXPECT_GE(number(rows[i], "line_pop_max"), number(rows[i], "line_pop_mean"));
  }
  for (const auto& row : rows) {
    EXPECT_EQ(number(row, "frames"), 4);
    EXPECT_EQ(number(row, "step_deg"), 2);
    EXPECT_GT(number(row, "seconds_per_frame"), 0);
    EXPECT_LT(number(row, "reprojection_error_mean"), number(row, "flicker_mean"));
    EXPECT_GE(number(row, "reprojection_error_max"), number(row, "reprojection_error_mean"));
  }
  const cv::Mat plot = cv::imread(dir + "/c.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(plot.empty());
  EXPECT_EQ(plot.cols, 1200);
  EXPECT_NE(r.output.find("coherence study 12/12  100%"), std::string::npos) << r.output;
}

TEST(Tradeoff, BadInputWritesNothing) {
  const std::string dir = temp_dir("tradeoff-bad");
  const std::string out = " -o " + dir + "/s.csv --plot " + dir + "/s.png";
  const std::string base = "tradeoff " + small_tree() + out;
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : std::vector<Case>{
           {base + " --study leaves", "allowed: foliage, ao, keyframes, coherence"},
           {base + " --study coherence --step 0", "--step"},
           {base + " --study coherence --frames 1", "--frames"},
           {base + " --study coherence --styles ink,,toon", "--styles"},
           {base + " --study coherence --styles nope", "nope"},
           {base + " --study coherence --every 2", "does not apply to --study coherence"},
           {base + " --study coherence --style ink", "--styles"},
           {base + " --study keyframes --step 2", "does not apply to --study keyframes"},
           {base + " --study keyframes --every 0", "--every"},
           {base + " --study keyframes --every 1,,4", "--every"},
           {base + " --study keyframes --every 2,2", "twice"},
           {base + " --study keyframes --frames 0", "--frames"},
           {base + " --study keyframes --axis w", "--axis"},
           {base + " --study keyframes --style ink", "blobs style"},
           {base + " --study keyframes --rays 4", "does not apply to --study keyframes"},
           {base + " --study keyframes --grids 32", "does not apply to --study keyframes"},
           {base + " --study ao --every 2", "does not apply to --study ao"},
           {base + " --study foliage --frames 8", "does not apply to --study foliage"},
           {base + " --study ao --fractions 1", "does not apply to --study ao"},
           {base + " --study foliage --rays 4", "does not apply to --study foliage"},
           {base + " --study foliage --size 64", "does not apply to --study foliage"},
           {base + " --study ao --rays 0", "--rays"},
           {base + " --study ao --rays 4,,8", "--rays"},
           {base + " --study ao --reference-rays 5000", "--reference-rays"},
           {base + " --study ao --shells 65", "[1, 64]"},
           {base + " --study ao --models none,phong", "--models"},
           {base + " --study ao --models constant,constant", "twice"},
           {base + " --study ao --repeats 0", "--repeats"},
           {base + " --study ao --size 0x5", "--size"},
           {base + " --study ao --set ao.alpha_rho=-1", "ao.alpha_rho"},
           {base + " --study ao --ka-min 2", "--ka-min"},
           {base + " --study foliage --set foliage.tau=-1", "foliage.tau"},
           {base + " --study foliage --set foliage.rhoo=1", "unknown key"},
           {base + " --study foliage --style nope", "nope"},
           {base + " --study foliage --fractions 0", "--fractions"},
           {base + " --study foliage --fractions 1.5", "(0, 1]"},
           {base + " --study foliage --fractions 1,,0.5", "--fractions"},
           {base + " --study foliage --fractions half", "--fractions"},
           {base + " --study foliage --grids 1", "[2, 1024]"},
           {base + " --study foliage --grids 32,2000", "--grids"},
           {base + " --study foliage --normal-sources normal", "--normal-sources"},
           {base + " --study foliage --encodings rgb", "--encodings"},
           {base + " --study foliage --thresholds half", "--thresholds"},
           {base + " --study foliage --ka-min 2", "--ka-min"},
           {"tradeoff " + small_tree() + " --study foliage -o " + dir + "/s.txt", "--output"},
           {"tradeoff " + small_tree() + " --study foliage -o " + dir + "/s.csv --plot " + dir +
                "/s.jpg",
            "--plot"},
           {"tradeoff " + small_tree() + out, "--study"},
       }) {
    expect_input_error(c.args, c.needle);
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "an output was left behind";
}

}  // namespace
}  // namespace sylva::test
