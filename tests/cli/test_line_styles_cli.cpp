// The ink and pen styles and their vector output through `sylva`: `sylva styles pen` lists the
// new keys with their ranges; pen is the same bytes twice; keys outside their range are one
// line, exit 2, naming the key and the range; `render -o X.svg|X.pdf` writes files that
// xmllint, rsvg-convert and pdftoppm read as the PNG's drawing; a closed outline is one closed
// path (a sphere, a cube); a style without lines, a bad --dpi or an unwritable path is an error
// that writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>

#include "tests/cli/cli_support.h"
#include "tests/cli/ink_metrics.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

TEST(LineStyles, StylesListsTheNewKeysWithRanges) {
  const RunResult r = run_sylva("styles pen");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* key :
       {"ink.detail", "lines.silhouette_width", "lines.interior_tone", "lines.wood_taper",
        "lines.detail_depth_width", "pen.tone", "pen.spacing", "pen.cross", "pen.seed"})
    EXPECT_NE(r.output.find(key), std::string::npos) << key;
  EXPECT_NE(r.output.find("hatching"), std::string::npos);
  EXPECT_NE(r.output.find("[0, 64] px at 1024 px"), std::string::npos);
  EXPECT_NE(run_sylva("styles ink").output.find("ink.detail"), std::string::npos);
}

TEST(LineStyles, PenIsTheSameBytesTwiceAndStippleDiffers) {
  const std::string dir = temp_dir("pen-twice");
  for (const char* name : {"a", "b"})
    ASSERT_EQ(run_sylva("render " + small_tree() + " --style pen --size 192 -o " + dir + "/" +
                        name + ".png")
                  .status,
              0);
  EXPECT_EQ(read_file(dir + "/a.png"), read_file(dir + "/b.png"));
  ASSERT_EQ(run_sylva("render " + small_tree() +
                      " --style pen --set pen.tone=stipple --size 192 -o " + dir + "/s.png")
                .status,
            0);
  EXPECT_NE(read_file(dir + "/a.png"), read_file(dir + "/s.png"));
}

TEST(LineStyles, KeysOutsideTheirRangeNameKeyAndRange) {
  const std::string out = temp_dir("line-keys") + "/x.png";
  const std::string base = "render " + small_tree() + " --size 64 --style pen -o " + out;
  expect_input_error(base + " --set ink.detail=64.5", "ink.detail");
  expect_input_error(base + " --set ink.detail=-1", "[0, 64]");
  expect_input_error(base + " --set lines.silhouette_width=0.2", "lines.silhouette_width");
  expect_input_error(base + " --set lines.wood_tone=1.1", "[0, 1]");
  expect_input_error(base + " --set pen.spacing=1", "pen.spacing");
  expect_input_error(base + " --set pen.tone=crosshatch", "hatching");
  expect_input_error(base + " --set pen.lightest=0.8 --set pen.darkest=0.5", "pen.darkest");
  EXPECT_FALSE(fs::exists(out));
}

// The ink of an SVG rendered by rsvg-convert, or a PDF by pdftoppm, at the PNG's size.
cv::Mat rendered(const std::string& file, const std::string& png, int size) {
  const RunResult r = file.ends_with(".svg")
                          ? run_command("rsvg-convert -w " + std::to_string(size) + " -h " +
                                        std::to_string(size) + " -b white -o " + png + " " + file)
                          : run_command("pdftoppm -png -r 72 -singlefile " + file + " " +
                                        png.substr(0, png.size() - 4));
  EXPECT_EQ(r.status, 0) << r.output;
  return cv::imread(png, cv::IMREAD_COLOR);
}

TEST(LineStyles, SvgAndPdfAreThePngsDrawing) {
  const std::string dir = temp_dir("vector-cli");
  const std::string args = "render " + small_tree() + " --style pen --size 384 -o " + dir;
  for (const char* ext : {".png", ".svg", ".pdf"})
    ASSERT_EQ(run_sylva(args + "/d" + ext).status, 0) << ext;
  EXPECT_EQ(run_command("xmllint --noout " + dir + "/d.svg").status, 0);
  const std::string svg = read_file(dir + "/d.svg");
  for (const char* layer : {"paper", "silhouette", "tone"})
    EXPECT_NE(svg.find(std::string("inkscape:label=\"") + layer + "\""), std::string::npos);
  EXPECT_EQ(read_file(dir + "/d.pdf").rfind("%PDF-", 0), 0u);
  const cv::Mat png = ink_pixels(cv::imread(dir + "/d.png", cv::IMREAD_COLOR));
  for (const char* ext : {".svg", ".pdf"}) {
    const cv::Mat other = ink_pixels(rendered(dir + "/d" + ext, dir + "/r.png", 384));
    ASSERT_EQ(other.size(), png.size()) << ext;
    EXPECT_GE(share_near(png, other, 1.5), 0.9) << ext;
    EXPECT_GE(share_near(other, png, 1.5), 0.9) << ext;
  }
  // The same command, the same bytes.
  ASSERT_EQ(run_sylva(args + "/again.svg").status, 0);
  EXPECT_EQ(svg, read_file(dir + "/again.svg"));
}

TEST(LineStyles, DpiSetsThePageAndTransparentDropsThePaper) {
  const std::string dir = temp_dir("vector-dpi");
  ASSERT_EQ(run_sylva("render " + small_tree() + " --style ink --size 300 --dpi 300 " +
                      "--background transparent -o " + dir + "/d.svg")
                .status,
            0);
  const std::string svg = read_file(dir + "/d.svg");
  EXPECT_NE(svg.find("width=\"25.4mm\" height=\"25.4mm\""), std::string::npos);
  EXPECT_EQ(svg.find("layer-paper"), std::string::npos);
  ASSERT_EQ(
      run_sylva("render " + small_tree() + " --style ink --size 300 --dpi 150 -o " + dir + "/d.pdf")
          .status,
      0);
  // 300 px at 150 dpi: a 2-inch page, 144 points.
  EXPECT_NE(read_file(dir + "/d.pdf").find("/MediaBox [ 0 0 144 144 ]"), std::string::npos);
}

// An .obj of a unit sphere (UV) or cube, for outlines with no junction.
std::string solid(const std::string& dir, bool cube) {
  const std::string path = dir + (cube ? "/cube.obj" : "/sphere.obj");
  std::ofstream f(path);
  if (cube) {
    f << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      << "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
      << "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
    return path;
  }
  const int rings = 24, segments = 48;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double t = 3.14159265 * i / rings, p = 2 * 3.14159265 * j / segments;
      f << "v " << std::sin(t) * std::cos(p) << ' ' << std::cos(t) << ' '
        << std::sin(t) * std::sin(p) << '\n';
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = i * segments + j + 1, b = i * segments + (j + 1) % segments + 1;
      const int c = a + segments, d = b + segments;
      f << "f " << a << ' ' << c << ' ' << b << "\nf " << b << ' ' << c << ' ' << d << '\n';
    }
  return path;
}

TEST(LineStyles, ClosedOutlinesAreClosedPaths) {
  const std::string dir = temp_dir("closed");
  for (bool cube : {false, true}) {
    const std::string svg = dir + (cube ? "/cube.svg" : "/sphere.svg");
    const RunResult r = run_sylva("render " + solid(dir, cube) + " --style outline --size 256 " +
                                  "--azimuth 30 --elevation 30 -o " + svg);
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string text = read_file(svg);
    const size_t start = text.find("id=\"layer-silhouette\"");
    ASSERT_NE(start, std::string::npos) << text;
    const std::string layer = text.substr(start, text.find("</g>", start) - start);
    const std::regex path("<path d=\"[^\"]*\"");
    int paths = 0, closed = 0;
    for (auto it = std::sregex_iterator(layer.begin(), layer.end(), path);
         it != std::sregex_iterator(); ++it) {
      ++paths;
      closed += it->str().ends_with("Z\"");
    }
    EXPECT_EQ(paths, 1) << (cube ? "cube" : "sphere");
    EXPECT_EQ(closed, 1) << (cube ? "cube" : "sphere");
  }
}

TEST(LineStyles, TurntableWritesOneSvgPerFrame) {
  const std::string dir = temp_dir("turntable-svg");
  const std::string args = "turntable " + small_tree() + " --style pen --frames 3 --size 160 -q";
  ASSERT_EQ(run_sylva(args + " -o " + dir + "/png/").status, 0);
  const RunResult r = run_sylva(args + " --frame-format svg -o " + dir + "/svg/");
  ASSERT_EQ(r.status, 0) << r.output;
  for (int i = 0; i < 3; ++i) {
    const std::string svg = dir + "/svg/frame-0000" + std::to_string(i) + ".svg";
    EXPECT_EQ(run_command("xmllint --noout " + svg).status, 0) << svg;
    const cv::Mat png =
        ink_pixels(cv::imread(dir + "/png/frame-0000" + std::to_string(i) + ".png"));
    const cv::Mat drawn = ink_pixels(rendered(svg, dir + "/r.png", 160));
    EXPECT_GE(share_near(png, drawn, 1.5), 0.9) << i;
    EXPECT_GE(share_near(drawn, png, 1.5), 0.9) << i;
  }
  expect_input_error("turntable " + small_tree() + " --style toon --frames 2 --size 64 " +
                         "--frame-format svg -o " + dir + "/toon/",
                     "no lines");
  expect_input_error(args + " --frame-format svg -o " + dir + "/t.mp4", "folder");
  expect_input_error(args + " --frame-format tiff -o " + dir + "/x/", "png, exr, svg or pdf");
  EXPECT_FALSE(fs::exists(dir + "/toon"));
}

TEST(LineStyles, BadVectorOutputsAreErrorsAndWriteNothing) {
  const std::string dir = temp_dir("vector-bad");
  const std::string scene = small_tree() + " --size 64 ";
  expect_input_error("render " + scene + "--style toon -o " + dir + "/t.svg", "ink, outline, pen");
  expect_input_error("render " + scene + "--style watercolor -o " + dir + "/t.pdf", "no lines");
  expect_input_error("render " + scene + "--style ink --dpi 10001 -o " + dir + "/t.svg", "--dpi");
  expect_input_error("render " + scene + "--style ink --dpi -2 -o " + dir + "/t.pdf", "--dpi");
  expect_input_error("render " + scene + "--style ink -o " + dir + "/missing/t.svg", "folder");
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace sylva::test
