// Golden images: small renders of the samples and the shared fern compared with
// tests/golden/*.png. A pixel fails when any channel differs by more than kTolerance; a
// render fails when more than kMaxFailing of its pixels fail. On failure NAME.actual.png and
// NAME.diff.png are written beside the golden. `make golden` (SYLVA_UPDATE_GOLDEN=1)
// rewrites them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

constexpr int kTolerance = 24;        // of 255, per channel
constexpr double kMaxFailing = 0.01;  // fraction of pixels

struct Case {
  const char* name;
  const char* scene;  // "sample:KIND" or a path relative to shared/
  const char* args;
};

std::string scene_path(const Case& c) {
  std::string s = c.scene;
  if (s.rfind("sample:", 0) != 0) return shared_dir() + "/" + s;
  std::string kind = s.substr(7);
  std::string p = temp_dir("golden-" + kind) + "/" + kind + ".glb";
  RunResult r = run_sylva("sample " + kind + " --leaves 1500 --seed 1 -o " + p);
  EXPECT_EQ(r.status, 0) << r.output;
  return p;
}

void check_golden(const Case& c) {
  std::string actual = temp_dir(std::string("golden-out-") + c.name) + "/actual.png";
  RunResult r = run_sylva("render " + scene_path(c) + " " + c.args + " -o " + actual);
  ASSERT_EQ(r.status, 0) << r.output;
  cv::Mat got = cv::imread(actual, cv::IMREAD_UNCHANGED);
  std::string golden = source_dir() + "/tests/golden/" + c.name + ".png";
  if (std::getenv("SYLVA_UPDATE_GOLDEN")) {
    cv::imwrite(golden, got);
    GTEST_SKIP() << "rewrote " << golden;
  }
  cv::Mat want = cv::imread(golden, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(want.empty()) << "missing " << golden << " (run `make golden`)";
  ASSERT_EQ(got.size(), want.size());
  ASSERT_EQ(got.type(), want.type());
  cv::Mat diff;
  cv::absdiff(got, want, diff);
  cv::Mat worst;
  cv::Mat channels[4];
  cv::split(diff, channels);
  worst = channels[0].clone();
  for (int i = 1; i < diff.channels(); ++i)
    worst = cv::max(worst, channels[i]);
  cv::Mat failing = worst > kTolerance;
  double fraction = cv::countNonZero(failing) / static_cast<double>(failing.total());
  if (fraction > kMaxFailing) {
    std::string base = source_dir() + "/tests/golden/" + c.name;
    cv::imwrite(base + ".actual.png", got);
    cv::imwrite(base + ".diff.png", worst * 4);
  }
  EXPECT_LE(fraction, kMaxFailing)
      << c.name << ": " << fraction * 100 << "% of pixels differ by more than " << kTolerance;
}

TEST(Golden, Tree) {
  check_golden({"tree", "sample:tree", "--size 256 --ssaa 2"});
}
TEST(Golden, Bush) {
  check_golden({"bush", "sample:bush", "--size 256 --ssaa 2"});
}
TEST(Golden, Conifer) {
  check_golden({"conifer", "sample:conifer", "--size 256 --ssaa 2"});
}
TEST(Golden, Fern) {
  check_golden({"fern", "assets/polyhaven_fern_02.glb", "--size 256 --ssaa 2 --elevation 35"});
}

// Every built-in preset besides standard on the samples and the fern (NAME-STYLE.png).
TEST(Golden, Presets) {
  const char* scenes[][3] = {{"tree", "sample:tree", ""},
                             {"bush", "sample:bush", ""},
                             {"conifer", "sample:conifer", ""},
                             {"fern", "assets/polyhaven_fern_02.glb", " --elevation 35"}};
  for (const char* style : {"expressive", "ink", "pen", "toon", "watercolor", "blobs"})
    for (const auto& s : scenes) {
      const std::string name = std::string(s[0]) + "-" + style;
      const std::string args = std::string("--size 256 --ssaa 2 --style ") + style + s[2];
      SCOPED_TRACE(name);
      check_golden({name.c_str(), s[1], args.c_str()});
    }
}

}  // namespace
}  // namespace sylva::test
