// Golden images of every image pass, at the library level (no CLI): each built-in style renders
// the 1500-leaf sample tree at 128² through make_sheet_scene and add_sheet_passes, and every
// image a pass other than the raster pass writes (the graph's observer sees each one) is compared
// with tests/golden/passes/STYLE-RESOURCE.png. 8-bit images are stored as they are; float images
// must lie in [0, 1] and are stored as 16-bit PNGs. A pixel fails when a channel differs by more
// than kTolerance (2 of 255; the whole-render goldens of tests/cli/test_golden.cpp allow 24), an
// image fails when more than kMaxFailing of its pixels do, and a pass that appears or disappears
// fails too. On failure NAME.actual.png and NAME.diff.png are written beside the golden;
// `make golden` (SYLVA_UPDATE_GOLDEN=1) rewrites them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "core/gl/depth_range.h"
#include "npr/leaf_clusters.h"
#include "samples/plants.h"
#include "styles/presets.h"
#include "styles/sheet.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

constexpr double kTolerance = 2.0 / 255.0;  // per channel, in [0, 1]
constexpr double kMaxFailing = 0.001;       // fraction of pixels

// The raster pass's targets: the style's inputs, not its passes' outputs.
bool raster_target(const std::string& name) {
  const std::string leaf = name.substr(name.rfind('/') + 1);
  for (const char* t : {"color", "normal", "depth", "position", "id", "ka", "albedo", "ao"})
    if (leaf == t) return true;
  return false;
}

struct Frame {
  Scene scene;
  std::unique_ptr<GlContext> context = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  RasterSetup setup;
  Frame() {
    PlantOptions po;
    po.leaves = 1500;
    scene = make_plant(po);
    assign_clusters(scene, {});
    raster = std::make_unique<Rasterizer>(*context);
    raster->upload(scene);
    setup.rasterizer = raster.get();
    setup.camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, 128, 128);
    fit_camera_depth(setup.camera, scene);
    setup.lighting = Lighting::three_point();
  }
};

// Every image the style's passes write, by resource name ('/' of scopes as '-').
std::map<std::string, cv::Mat> pass_images(const Frame& frame, const std::string& name) {
  const Style style(name);
  std::map<std::string, cv::Mat> images;
  RenderGraph graph;
  graph.set_observer([&](const std::string& resource, const std::any& value) {
    const cv::Mat* m = std::any_cast<cv::Mat>(&value);
    if (m == nullptr || raster_target(resource)) return;
    std::string file = resource;
    std::replace(file.begin(), file.end(), '/', '-');
    images[file] = m->clone();
  });
  add_sheet_passes(graph, {&style}, make_sheet_scene(frame.scene, frame.setup, FoliageRun{}, 1));
  graph.execute();
  return images;
}

// As stored: 8-bit as it is, float (in [0, 1]) as 16-bit.
cv::Mat stored(const cv::Mat& m, const std::string& name) {
  if (m.depth() == CV_8U) return m;
  EXPECT_EQ(m.depth(), CV_32F) << name;
  EXPECT_TRUE(cv::checkRange(m, true, nullptr, 0.0, 1.0 + 1e-6)) << name << " leaves [0, 1]";
  cv::Mat wide;
  m.convertTo(wide, CV_16U, 65535.0);
  return wide;
}

// In [0, 1], channel by channel.
cv::Mat unit(const cv::Mat& m) {
  cv::Mat f;
  m.convertTo(f, CV_32F, m.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  return f;
}

void compare(const std::string& name, const cv::Mat& got) {
  const std::string golden = source_dir() + "/tests/golden/passes/" + name + ".png";
  const cv::Mat want = cv::imread(golden, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(want.empty()) << "missing " << golden << " (run `make golden`)";
  ASSERT_EQ(got.size(), want.size()) << name;
  ASSERT_EQ(got.type(), want.type()) << name;
  cv::Mat diff;
  cv::absdiff(unit(got), unit(want), diff);
  cv::Mat worst = diff.reshape(1, int(diff.total())).clone();
  cv::reduce(worst, worst, 1, cv::REDUCE_MAX);
  const double fraction = cv::countNonZero(worst > kTolerance) / double(worst.total());
  if (fraction > kMaxFailing) {
    const std::string base = source_dir() + "/tests/golden/passes/" + name;
    cv::imwrite(base + ".actual.png", got);
    cv::Mat picture;
    worst.reshape(1, got.rows).convertTo(picture, CV_8U, 4 * 255.0);
    cv::imwrite(base + ".diff.png", picture);
  }
  EXPECT_LE(fraction, kMaxFailing)
      << name << ": " << fraction * 100 << "% of pixels differ by more than 2 of 255";
}

// The built-in style a golden file belongs to: the longest name it starts with before a '-'
// ("toon-ink-toon-final.png" is toon-ink's, not toon's).
std::string owner(const std::string& file) {
  std::string best;
  for (const std::string& name : builtin_preset_names())
    if (file.starts_with(name + "-") && name.size() > best.size()) best = name;
  return best;
}

class PassGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(PassGolden, EveryPassOutputMatches) {
  static const Frame frame;
  const std::string style = GetParam();
  const std::map<std::string, cv::Mat> images = pass_images(frame, style);
  const std::string dir = source_dir() + "/tests/golden/passes";
  if (std::getenv("SYLVA_UPDATE_GOLDEN")) {
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(dir))
      if (owner(e.path().filename().string()) == style) fs::remove(e.path());
    for (const auto& [resource, image] : images)
      cv::imwrite(dir + "/" + style + "-" + resource + ".png", stored(image, resource));
    GTEST_SKIP() << "rewrote the goldens of " << style;
  }
  size_t goldens = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string file = e.path().filename().string();
    if (owner(file) == style && !file.ends_with(".actual.png") && !file.ends_with(".diff.png"))
      ++goldens;
  }
  EXPECT_EQ(goldens, images.size()) << style << ": a pass output appeared or disappeared";
  for (const auto& [resource, image] : images) {
    SCOPED_TRACE(style + " " + resource);
    compare(style + "-" + resource, stored(image, resource));
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltInStyles, PassGolden, ::testing::ValuesIn(builtin_preset_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;  // "pen-and-wash" -> "pen_and_wash"
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace sylva::test
