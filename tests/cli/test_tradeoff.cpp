// sylva tradeoff: a quick foliage sweep writes the CSV (header, one row per run and
// encoding) and a PNG chart that decodes, with a progress line per run on a pipe; bad
// studies and out-of-range lists exit 2 with one line and write nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

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

TEST(Tradeoff, BadInputWritesNothing) {
  const std::string dir = temp_dir("tradeoff-bad");
  const std::string out = " -o " + dir + "/s.csv --plot " + dir + "/s.png";
  const std::string base = "tradeoff " + small_tree() + out;
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : std::vector<Case>{
           {base + " --study ao", "allowed: foliage"},
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
