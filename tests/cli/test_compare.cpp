// sylva compare end to end: a sheet of every built-in style, a two-key sweep of the Luft
// parameters as a table (Fig. 3), shared preprocessing, and bad input (exit 2, no sheet).
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

TEST(Compare, EveryBuiltInStyleOnOneSheet) {
  const std::string dir = temp_dir("compare");
  const std::string out = dir + "/sheet.png";
  const RunResult r =
      run_sylva("compare " + small_tree() + " --size 96 --graph " + dir + "/g.dot -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  // Ten styles; two Luft preprocessings: expressive, toon and watercolor share one, ink,
  // outline, pen and the stacks over ink (whose rho comes from ink.detail at this picture's
  // scale) the other.
  EXPECT_NE(r.output.find("10 cells"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 foliage preprocessing"), std::string::npos) << r.output;
  const cv::Mat sheet = cv::imread(out, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(sheet.empty());
  EXPECT_EQ(sheet.channels(), 4);
  // Four columns of 96 px cells and three rows with labels.
  EXPECT_GT(sheet.cols, 4 * 96);
  EXPECT_LT(sheet.cols, 4 * 96 + 40);
  EXPECT_GT(sheet.rows, 3 * 96 + 3 * 20);
  const std::string dot = read_file(dir + "/g.dot");
  for (const char* pass :
       {"cell-2/leaf-layer", "cell-3/ink-strokes", "cell-4/hatching", "cell-6/watercolor",
        "cell-7/watercolor/watercolor", "cell-7/ink/lines-over", "cell-8/toon/toon",
        "cell-8/ink/lines-over", "cell-9/blobs", "foliage-0/foliage-illumination"})
    EXPECT_NE(dot.find(pass), std::string::npos) << pass;
  // Same inputs, same bytes.
  const RunResult again =
      run_sylva("compare " + small_tree() + " --size 96 -q -o " + dir + "/again.png");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(read_file(out), read_file(dir + "/again.png"));
}

// Luft Fig. 3 as a table: rho down, tau across; one preprocessing per cell, rows differ.
TEST(Compare, RhoTauSweepIsATable) {
  const std::string dir = temp_dir("compare-sweep");
  const std::string out = dir + "/fig3.png";
  const RunResult r = run_sylva("compare " + small_tree() +
                                " --style expressive --sweep foliage.rho=3%,20% "
                                "--sweep foliage.tau=auto,1,4 --size 64 -o " +
                                out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("6 cells"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("6 foliage preprocessing"), std::string::npos) << r.output;
  const cv::Mat sheet = cv::imread(out, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(sheet.empty());
  EXPECT_GT(sheet.cols, 3 * 64);
  EXPECT_LT(sheet.cols, 4 * 64);
  // A sweep of a line parameter keeps one raster pass and one preprocessing.
  const RunResult ink = run_sylva("compare " + small_tree() +
                                  " --styles ink --sweep edges.normal_threshold=10,20,40 "
                                  "--size 64 -o " +
                                  dir + "/ink.png");
  ASSERT_EQ(ink.status, 0) << ink.output;
  EXPECT_NE(ink.output.find("3 cells, 1 raster pass(es), 1 foliage"), std::string::npos)
      << ink.output;
}

TEST(Compare, BadInputExitsTwoAndWritesNothing) {
  const std::string dir = temp_dir("compare-bad");
  const std::string out = dir + "/sheet.png";
  const std::string base = "compare " + small_tree() + " --size 32 -o " + out + " ";
  write_file(dir + "/cycle.toml", "inherits = [\"cycle.toml\"]\n");
  expect_input_error(base + "--styles ink,sketch", "sketch");
  expect_input_error(base + "--styles ink," + dir + "/cycle.toml", "cycle");
  expect_input_error(base + "--style ink --sweep edges.width", "--sweep");
  expect_input_error(base + "--style ink --sweep edges.width=1,200", "edges.width");
  expect_input_error(base + "--style ink --sweep edges.widht=1,2", "unknown key");
  expect_input_error(base + "--style expressive --sweep foliage.rho=4%,-1", "rho");
  expect_input_error(base + "--style ink --styles toon", "--style");
  expect_input_error(base + "--set ink.fill=2", "ink.fill");
  expect_input_error(base + "--columns 300", "--columns");
  expect_input_error(base + "--label-lines 21", "--label-lines");
  expect_input_error("compare " + small_tree() + " -o " + dir + "/sheet.gif", "--output");
  EXPECT_FALSE(file_exists(out));
}

}  // namespace
}  // namespace sylva::test
