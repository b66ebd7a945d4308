// The sylva executable end to end: help, errors (one line, exit 2, nothing written),
// determinism, lossless buffers, and glTF validity of what it writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

TEST(Cli, HelpListsCommands) {
  RunResult r = run_sylva("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* cmd : {"sample", "info", "render", "buffers"})
    EXPECT_NE(r.output.find(cmd), std::string::npos) << cmd;
  RunResult rr = run_sylva("render --help");
  EXPECT_EQ(rr.status, 0);
  EXPECT_NE(rr.output.find("--elevation"), std::string::npos);
}

TEST(Cli, UsageErrorsExitTwo) {
  expect_input_error("", "");
  expect_input_error("frobnicate", "frobnicate");
  expect_input_error("render " + small_tree(), "--output");
}

TEST(Cli, BadOptionValuesNameTheOption) {
  std::string dir = temp_dir("bad-options");
  std::string out = dir + "/x.png";
  std::string base = "render " + small_tree() + " -o " + out + " ";
  expect_input_error(base + "--size 0x10", "--size");
  expect_input_error(base + "--size 16385", "--size");
  expect_input_error(base + "--size banana", "--size");
  expect_input_error(base + "--ssaa 0", "--ssaa");
  expect_input_error(base + "--ssaa 5", "--ssaa");
  expect_input_error(base + "--elevation 90", "--elevation");
  expect_input_error(base + "--elevation -89.5", "--elevation");
  expect_input_error(base + "--fov 0.5", "--fov");
  expect_input_error(base + "--fov 151", "--fov");
  expect_input_error(base + "--distance -1", "--distance");
  expect_input_error(base + "--ambient 1.01", "--ambient");
  expect_input_error(base + "--ambient -0.01", "--ambient");
  expect_input_error(base + "--background purple", "--background");
  expect_input_error(base + "--style nonesuch", "--style");
  expect_input_error(base + "--light sun:0,1,0", "--light");
  expect_input_error(base + "--light dir:0,0,0", "--light");
  expect_input_error(base + "--light dir:0,1,0:10.5", "--light");
  expect_input_error(base + "--light dir:0,1,0:-0.1", "--light");
  expect_input_error(base + "--light dir:0,1,0:1:sky", "--light");
  std::string nine;
  for (int i = 0; i < 9; ++i)
    nine += " --light dir:0,1,0";
  expect_input_error(base + nine, "--light");
  expect_input_error(base + "--foliage nomatch*", "--foliage");
  expect_input_error(base + "--clusters 4097", "--clusters");
  expect_input_error(base + "--clusters -1", "--clusters");
  expect_input_error("render " + small_tree() + " -o " + dir + "/x.bmp", "--output");
  expect_input_error("render " + small_tree() + " -o " + dir + "/missing/x.png", "--output");
  expect_input_error("buffers " + small_tree() + " --out-dir " + dir + "/b --buffers color,nope",
                     "--buffers");
  expect_input_error("buffers " + small_tree() + " --out-dir " + dir + "/b --id leaf", "--id");
  expect_input_error("sample oak -o " + dir + "/t.glb", "oak");
  expect_input_error("sample tree --leaves 99 -o " + dir + "/t.glb", "--leaves");
  expect_input_error("sample tree --leaves 2000001 -o " + dir + "/t.glb", "--leaves");
  EXPECT_TRUE(fs::is_empty(dir)) << "an output was left behind";
}

TEST(Cli, ParameterExtremesRender) {
  std::string dir = temp_dir("extremes");
  for (const char* opts : {"--size 1 --ssaa 4", "--size 64x16 --elevation 89 --fov 150",
                           "--size 16x64 --elevation -89 --fov 1 --ambient 0",
                           "--size 32 --ortho --ambient 1 --background transparent",
                           "--size 32 --distance 100 --azimuth -720",
                           "--size 32 --light dir:1,1,1:10:scene --light point:0,5,5:0",
                           "--size 32 --light dir:0,1,0 --light dir:0,1,0 --light dir:0,1,0 "
                           "--light dir:0,1,0 --light dir:0,1,0 --light dir:0,1,0 "
                           "--light dir:0,1,0 --light dir:1,0,0"}) {
    std::string out = dir + "/e.png";
    RunResult r = run_sylva("render " + small_tree() + " " + opts + " -o " + out);
    EXPECT_EQ(r.status, 0) << opts << "\n" << r.output;
    EXPECT_FALSE(cv::imread(out, cv::IMREAD_UNCHANGED).empty()) << opts;
  }
}

// The Luft options: bad values name the option and write nothing; the ends of each range
// render; a tau above every density is a clear error naming rho, tau and the density range.
TEST(Cli, FoliageIlluminationOptions) {
  std::string dir = temp_dir("luft");
  std::string out = dir + "/x.png";
  std::string base = "render " + small_tree() + " --style expressive --size 32 -o " + out + " ";
  for (const char* bad : {"--rho 0",           "--rho -1",         "--rho 0%",
                          "--rho banana",      "--tau -1",         "--tau nan",
                          "--fraction 0",      "--fraction 1.01",  "--grid 1",
                          "--grid 1025",       "--blend -0.1",     "--blend 1.1",
                          "--ka-min 1.01",     "--ka-min -0.01",   "--d-min 0",
                          "--exponent 0",      "--exponent 100.5", "--normal-source sky",
                          "--ka-encoding rgb", "--smooth 101",     "--decimate 0"}) {
    const std::string option = std::string(bad).substr(0, std::string(bad).find(' '));
    expect_input_error(base + bad, option);
  }
  expect_input_error(base + "--tau 1e9", "--tau");  // no surface: rho and range named
  RunResult r = run_sylva(base + "--tau 1e9");
  EXPECT_NE(r.output.find("rho"), std::string::npos) << r.output;
  EXPECT_FALSE(file_exists(out));
  expect_input_error(base + "--rho 1% --grid 2", "--grid");  // nodes miss every kernel
  EXPECT_FALSE(file_exists(out));
  for (const char* ok :
       {"--rho 2% --grid 96", "--rho 500% --grid 2 --fraction 0.001", "--tau 0 --blend 0",
        "--ka-min 0 --exponent 0.01 --d-min 1e-6", "--ka-min 1 --exponent 100",
        "--normal-source gradient --ka-encoding attribute --per-triangle",
        "--grid 256 --smooth 3 --decimate 0.5"}) {
    RunResult rr = run_sylva(base + ok);
    EXPECT_EQ(rr.status, 0) << ok << "\n" << rr.output;
    EXPECT_FALSE(cv::imread(out, cv::IMREAD_UNCHANGED).empty()) << ok;
  }
  // Buffers: realigned-scaled normals carry ka in their length; realigned ones are unit.
  for (const char* mode : {"realigned", "realigned-scaled"}) {
    const std::string bdir = dir + "/" + mode;
    RunResult b =
        run_sylva("buffers " + small_tree() + " --size 64 --buffers normal,ka --normals " + mode +
                  " --out-dir " + bdir + " --surface-out " + dir + "/s.glb");
    ASSERT_EQ(b.status, 0) << b.output;
    const cv::Mat n = cv::imread(bdir + "/normal.tiff", cv::IMREAD_UNCHANGED);
    const cv::Mat ka = cv::imread(bdir + "/ka.tiff", cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(n.empty());
    double worst = 0.0;
    for (int y = 0; y < n.rows; ++y)
      for (int x = 0; x < n.cols; ++x) {
        if (ka.at<float>(y, x) <= 0.0f) continue;
        const double len = cv::norm(n.at<cv::Vec3f>(y, x));
        const double want = std::string(mode) == "realigned" ? 1.0 : ka.at<float>(y, x);
        worst = std::max(worst, std::abs(len - want));
      }
    EXPECT_LT(worst, 2e-3) << mode;
    EXPECT_TRUE(file_exists(dir + "/s.glb"));
  }
  expect_input_error("buffers " + small_tree() + " --normals bent --out-dir " + dir + "/b",
                     "--normals");
}

TEST(Cli, StylesPresetsAndSet) {
  RunResult list = run_sylva("styles");
  ASSERT_EQ(list.status, 0) << list.output;
  for (const char* s : {"standard", "expressive", "ink", "toon", "watercolor", "blobs"})
    EXPECT_NE(list.output.find(s), std::string::npos) << s;
  RunResult ink = run_sylva("styles ink");
  ASSERT_EQ(ink.status, 0) << ink.output;
  EXPECT_NE(ink.output.find("edges.width"), std::string::npos);
  EXPECT_NE(ink.output.find("[0.25, 16] px"), std::string::npos) << ink.output;

  const std::string dir = temp_dir("presets-cli");
  const std::string out = dir + "/x.png";
  const std::string base = "render " + small_tree() + " --size 48 -o " + out + " ";
  write_file(dir + "/bad.toml", "builder = \"ink\"\n[edges]\nwidth = 100\n");
  expect_input_error(base + "--style " + dir + "/bad.toml", "bad.toml");
  write_file(dir + "/syntax.toml", "builder = \"ink\n");
  expect_input_error(base + "--style " + dir + "/syntax.toml", "line 1");
  expect_input_error(base + "--style ink --set edges.width=0", "edges.width");
  expect_input_error(base + "--style ink --set edges.widht=2", "unknown key");
  expect_input_error(base + "--style ink --set edges.min_width=4.1", "edges.min_width");
  expect_input_error(base + "--style ink --set edges.min_width=-0.1", "edges.min_width");
  expect_input_error(base + "--style ink --set edges.min_length=-1", "edges.min_length");
  expect_input_error(base + "--style ink --set edges.min_length=257", "edges.min_length");
  expect_input_error(base + "--style toon --set toon.shadow_map_size=63", "toon.shadow_map_size");
  expect_input_error(base + "--style sketch", "sketch");
  EXPECT_FALSE(file_exists(out));
  write_file(dir + "/mine.toml", "inherits = [\"ink\"]\n[edges]\nwidth = 3\n");
  RunResult mine = run_sylva(base + "--style " + dir + "/mine.toml --set ink.fill=0.5");
  EXPECT_EQ(mine.status, 0) << mine.output;
  EXPECT_TRUE(file_exists(out));
  for (const char* ends : {"--set edges.min_width=0 --set edges.min_length=0",
                           "--set edges.min_width=4 --set edges.min_length=256"}) {
    RunResult r = run_sylva(base + "--style ink " + ends);
    EXPECT_EQ(r.status, 0) << ends << ": " << r.output;
  }
  // An explicit foliage option wins over the preset and is checked like it.
  expect_input_error(base + "--style expressive --grid 1", "--grid");
}

TEST(Cli, BadScenesExitTwoAndWriteNothing) {
  std::string dir = temp_dir("bad-scenes");
  std::string out = dir + "/out.png";
  expect_input_error("render " + dir + "/nope.glb -o " + out, "no such file");
  write_file(dir + "/empty.glb", "");
  expect_input_error("render " + dir + "/empty.glb -o " + out, "empty.glb");
  write_file(dir + "/bad.gltf", "{ \"asset\": { \"version\": ");
  expect_input_error("info " + dir + "/bad.gltf", "bad.gltf");
  std::string fern = read_file(fern_path());
  write_file(dir + "/truncated.glb", fern.substr(0, fern.size() / 2));
  expect_input_error("render " + dir + "/truncated.glb -o " + out, "truncated.glb");
  write_file(dir + "/scene.xyz", "hello");
  expect_input_error("info " + dir + "/scene.xyz", ".glb");
  EXPECT_FALSE(file_exists(out));
}

TEST(Cli, SameCommandTwiceGivesSameBytes) {
  std::string dir = temp_dir("determinism");
  for (int i = 0; i < 2; ++i) {
    std::string n = std::to_string(i);
    ASSERT_EQ(run_sylva("sample bush --leaves 500 --seed 9 -o " + dir + "/b" + n + ".glb").status,
              0);
    ASSERT_EQ(
        run_sylva("render " + small_tree() + " --size 128 --ssaa 2 -o " + dir + "/r" + n + ".png")
            .status,
        0);
  }
  EXPECT_EQ(read_file(dir + "/b0.glb"), read_file(dir + "/b1.glb"));
  EXPECT_EQ(read_file(dir + "/r0.png"), read_file(dir + "/r1.png"));
  ASSERT_EQ(run_sylva("sample bush --leaves 500 --seed 10 -o " + dir + "/b2.glb").status, 0);
  EXPECT_NE(read_file(dir + "/b0.glb"), read_file(dir + "/b2.glb"));
}

TEST(Cli, BuffersReadBackExactly) {
  std::string dir = temp_dir("buffers") + "/out";
  RunResult r = run_sylva("buffers " + small_tree() + " --size 96x64 --out-dir " + dir +
                          " --id cluster --background transparent --graph " + dir + ".dot");
  ASSERT_EQ(r.status, 0) << r.output;
  cv::Mat color = cv::imread(dir + "/color.png", cv::IMREAD_UNCHANGED);
  cv::Mat normal = cv::imread(dir + "/normal.tiff", cv::IMREAD_UNCHANGED);
  cv::Mat depth = cv::imread(dir + "/depth.tiff", cv::IMREAD_UNCHANGED);
  cv::Mat position = cv::imread(dir + "/position.tiff", cv::IMREAD_UNCHANGED);
  cv::Mat id = cv::imread(dir + "/id.tiff", cv::IMREAD_UNCHANGED);
  cv::Mat ka = cv::imread(dir + "/ka.tiff", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(color.type(), CV_8UC4);
  ASSERT_EQ(normal.type(), CV_32FC3);
  ASSERT_EQ(depth.type(), CV_32FC1);
  ASSERT_EQ(position.type(), CV_32FC3);
  ASSERT_EQ(id.type(), CV_32FC1);
  ASSERT_EQ(ka.type(), CV_32FC1);
  EXPECT_EQ(normal.size(), cv::Size(96, 64));
  int covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x) {
      float d = depth.at<float>(y, x);
      cv::Vec3f n = normal.at<cv::Vec3f>(y, x);
      cv::Vec3f p = position.at<cv::Vec3f>(y, x);
      float i = id.at<float>(y, x);
      EXPECT_EQ(i, std::floor(i));
      if (d == 0) {
        EXPECT_EQ(i, 0.0f);
        EXPECT_EQ(color.at<cv::Vec4b>(y, x)[3], 0);
        continue;
      }
      ++covered;
      EXPECT_GT(i, 0.0f);
      EXPECT_NEAR(cv::norm(n), 1.0, 1e-3);
      // OpenCV reads the file's R, G, B (x, y, z) as channels 2, 1, 0.
      EXPECT_NEAR(-p[0], d, 1e-3 * d);  // depth is the distance along the view axis
      EXPECT_GE(ka.at<float>(y, x), 0.0f);
      EXPECT_LE(ka.at<float>(y, x), 1.0f);
    }
  EXPECT_GT(covered, 96 * 64 / 20);
  for (const char* f : {"normal", "depth", "position", "id", "ka"})
    EXPECT_TRUE(file_exists(dir + "/" + f + ".preview.png")) << f;
  std::string cam = read_file(dir + "/camera.json");
  EXPECT_NE(cam.find("\"projection\""), std::string::npos);
  EXPECT_NE(read_file(dir + ".dot").find("raster"), std::string::npos);
}

// ao.model feeds the AO buffer: float32 in [0, 1], background 0; bad ao.* values exit 2.
TEST(Cli, BuffersWriteAmbientOcclusion) {
  const std::string dir = temp_dir("buffers-ao") + "/out";
  const RunResult r = run_sylva("buffers " + small_tree() + " --size 64x48 --out-dir " + dir +
                                " --buffers ao,depth --set ao.model=hegeman-sphere");
  ASSERT_EQ(r.status, 0) << r.output;
  const cv::Mat ao = cv::imread(dir + "/ao.tiff", cv::IMREAD_UNCHANGED);
  const cv::Mat depth = cv::imread(dir + "/depth.tiff", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(ao.type(), CV_32FC1);
  ASSERT_EQ(ao.size(), cv::Size(64, 48));
  int dark = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const float a = ao.at<float>(y, x);
      ASSERT_TRUE(a >= 0.0f && a <= 1.0f) << a;
      if (depth.at<float>(y, x) == 0.0f) {
        EXPECT_EQ(a, 0.0f);
      }
      dark += depth.at<float>(y, x) > 0.0f && a < 0.9f ? 1 : 0;
    }
  EXPECT_GT(dark, 0);
  EXPECT_TRUE(file_exists(dir + "/ao.preview.png"));
  const std::string base = "buffers " + small_tree() + " --size 32x32 --out-dir " + dir + "2 ";
  expect_input_error(base + "--set ao.model=foo", "ao.model");
  expect_input_error(base + "--set ao.shells=65", "ao.shells");
  expect_input_error(base + "--set ao.rays=0", "ao.rays");
  expect_input_error(base + "--set ao.constant=2", "ao.constant");
  expect_input_error(base + "--set ao.alpha_rho=-1", "ao.alpha_rho");
}

TEST(Cli, InfoReportsTheSample) {
  RunResult r = run_sylva("info --json " + small_tree());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"leaves\": 2"), std::string::npos) << r.output;  // ~2000
  EXPECT_NE(r.output.find("hierarchy"), std::string::npos) << r.output;
  RunResult f = run_sylva("info " + fern_path());
  ASSERT_EQ(f.status, 0) << f.output;
  EXPECT_NE(f.output.find("MASK"), std::string::npos) << f.output;
}

// Every .glb Sylva writes passes the Khronos glTF Validator with 0 errors.
TEST(Cli, WrittenGlbPassesTheKhronosValidator) {
  ASSERT_TRUE(gltf_validator_installed()) << "run scripts/setup.sh (npm install of gltf-validator)";
  std::string dir = temp_dir("validator");
  for (const char* kind : {"tree", "bush", "conifer"}) {
    std::string glb = dir + "/" + kind + ".glb";
    ASSERT_EQ(run_sylva(std::string("sample ") + kind + " --leaves 300 -o " + glb).status, 0);
    RunResult v = validate_gltf(glb);
    EXPECT_EQ(v.status, 0) << kind << ": " << v.output;
    EXPECT_NE(v.output.find("errors=0"), std::string::npos) << kind << ": " << v.output;
  }
}

}  // namespace
}  // namespace sylva::test
