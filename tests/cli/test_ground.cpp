// End-to-end tests of `sylva sample grass` (--blades at both ends of its range and just
// outside, deterministic bytes, the grass role in `sylva info`) and of --ground,
// --ground-color and ao.solid_angle on `sylva buffers` (the ground and the grass get AO).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

const std::string& grass_patch() {
  return sampled_scene("grass", "grass --blades 500");
}

TEST(Ground, SampleGrassBladesRange) {
  const std::string dir = temp_dir("grass-range");
  for (const char* ok : {"1", "200000", "0"}) {
    const RunResult r =
        run_sylva("sample grass --blades " + std::string(ok) + " -o " + dir + "/g.glb");
    EXPECT_EQ(r.status, 0) << ok << "\n" << r.output;
  }
  expect_input_error("sample grass --blades 200001 -o " + dir + "/x.glb", "--blades");
  expect_input_error("sample grass --blades -1 -o " + dir + "/x.glb", "--blades");
  expect_input_error("sample tree --blades 10 -o " + dir + "/x.glb", "--blades");
  expect_input_error("sample grass --leaves 100 -o " + dir + "/x.glb", "--leaves");
  EXPECT_FALSE(file_exists(dir + "/x.glb"));
}

TEST(Ground, SampleGrassIsDeterministicAndKnownAsGrass) {
  const std::string dir = temp_dir("grass-bytes");
  for (const char* name : {"a", "b"})
    ASSERT_EQ(run_sylva("sample grass --seed 4 -o " + dir + "/" + name + ".glb").status, 0);
  ASSERT_EQ(run_sylva("sample grass --seed 5 -o " + dir + "/c.glb").status, 0);
  EXPECT_EQ(read_file(dir + "/a.glb"), read_file(dir + "/b.glb"));
  EXPECT_NE(read_file(dir + "/a.glb"), read_file(dir + "/c.glb"));
  const RunResult info = run_sylva("info --json " + dir + "/a.glb");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("\"grass\": 6000"), std::string::npos) << info.output;  // 2000 x 3
}

// Covered pixels (depth > 0) and their AO range.
struct Coverage {
  int covered = 0;
  float lo = 1.0f, hi = 0.0f;
};
Coverage coverage(const std::string& dir) {
  const cv::Mat ao = cv::imread(dir + "/ao.tiff", cv::IMREAD_UNCHANGED);
  const cv::Mat depth = cv::imread(dir + "/depth.tiff", cv::IMREAD_UNCHANGED);
  Coverage c;
  EXPECT_EQ(ao.type(), CV_32FC1);
  if (ao.type() != CV_32FC1 || depth.type() != CV_32FC1) return c;
  for (int y = 0; y < ao.rows; ++y)
    for (int x = 0; x < ao.cols; ++x) {
      const float a = ao.at<float>(y, x);
      EXPECT_TRUE(std::isfinite(a) && a >= 0.0f && a <= 1.0f) << a;
      if (depth.at<float>(y, x) == 0.0f) continue;
      ++c.covered;
      c.lo = std::min(c.lo, a);
      c.hi = std::max(c.hi, a);
    }
  return c;
}

TEST(Ground, GroundPlaneReceivesTheCrownsOcclusion) {
  const std::string dir = temp_dir("ground");
  const std::string base = "buffers " + small_tree() + " --size 64x64 --buffers ao,depth ";
  ASSERT_EQ(run_sylva(base + "--out-dir " + dir + "/plain --set ao.model=hegeman-sphere").status,
            0);
  for (const char* mode : {"exact", "paper"}) {
    const std::string out = dir + "/" + mode;
    const RunResult r = run_sylva(base + "--ground --ground-color '#808070' --out-dir " + out +
                                  " --set ao.model=hegeman-sphere --set ao.solid_angle=" + mode);
    ASSERT_EQ(r.status, 0) << r.output;
    const Coverage plain = coverage(dir + "/plain"), ground = coverage(out);
    // The ground fills the lower part of the frame; the framing does not change, so the
    // tree still covers what it covered.
    EXPECT_GT(ground.covered, plain.covered + 64 * 64 / 5) << mode;
    EXPECT_GT(ground.hi, 0.95f) << mode;  // open ground far from the tree
  }
  expect_input_error(base + "--out-dir " + dir + "/x --ground --ground-color red",
                     "--ground-color");
  expect_input_error(base + "--out-dir " + dir + "/x --ground --ground-color '#12345'",
                     "--ground-color");
  expect_input_error(base + "--out-dir " + dir + "/x --set ao.solid_angle=approx",
                     "ao.solid_angle");
}

TEST(Ground, GrassPatchGetsGrassVisibility) {
  const std::string dir = temp_dir("grass-ao") + "/out";
  const RunResult ok = run_sylva("buffers " + grass_patch() + " --size 64x64 --out-dir " + dir +
                                 " --buffers ao,depth --set ao.model=hegeman-sphere");
  ASSERT_EQ(ok.status, 0) << ok.output;
  const Coverage c = coverage(dir);
  EXPECT_GT(c.covered, 100);
  EXPECT_LT(c.lo, 0.2f);  // Eq. 9: dark at the roots
  EXPECT_GT(c.hi, 0.6f);  // bright at the tips
}

}  // namespace
}  // namespace sylva::test
