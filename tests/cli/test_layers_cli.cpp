// Stacked presets through `sylva` (styles/style.h: layers): `pen-and-wash` and `toon-ink` lay
// the `ink` style's own lines over their paint (the same strokes, and the same line pixels
// within 1 px), the paint under the lines is the first layer's picture, which the SVG carries
// as an embedded image that rsvg-convert draws under the vector lines as the PNG shows them;
// a layer that is not a line style after the first is one line, exit 2.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 256;

std::string render(const std::string& style, const std::string& out) {
  const RunResult r = run_sylva("render " + small_tree() + " --style " + style + " --size " +
                                std::to_string(kSize) + " -o " + out);
  EXPECT_EQ(r.status, 0) << style << ": " << r.output;
  return out;
}

// The SVG without its paint layer (the strokes and the paper). Not a std::regex: its matcher
// recurses per character and overflows the stack on the embedded image's long line.
std::string without_paint(std::string svg) {
  const size_t start = svg.find("  <g inkscape:groupmode=\"layer\" id=\"layer-paint\"");
  if (start == std::string::npos) return svg;
  const std::string close = "  </g>\n";
  const size_t end = svg.find(close, start);
  if (end == std::string::npos) return svg;
  return svg.erase(start, end + close.size() - start);
}

// Share of the pixels `a` marks whose 3 x 3 neighbourhood holds one `b` marks.
double agreement(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat near;
  cv::dilate(b, near, cv::Mat::ones(3, 3, CV_8U));
  const double n = cv::countNonZero(a);
  return n > 0 ? cv::countNonZero(a & near) / n : 0.0;
}

TEST(Layers, StackedPresetsLayTheInkStylesLinesOverTheirPaint) {
  const std::string dir = temp_dir("layers-cli");
  const cv::Mat ink = cv::imread(render("ink", dir + "/ink.png"), cv::IMREAD_GRAYSCALE);
  const std::string ink_svg = read_file(render("ink", dir + "/ink.svg"));
  // The ink's solid line pixels: black on white paper.
  const cv::Mat ink_lines = ink < 8;
  ASSERT_GT(cv::countNonZero(ink_lines), 500);
  for (const char* style : {"pen-and-wash", "toon-ink"}) {
    const std::string base = dir + "/" + style;
    const cv::Mat stacked = cv::imread(render(style, base + ".png"), cv::IMREAD_GRAYSCALE);
    const double a = agreement(ink_lines, stacked < 8);
    EXPECT_GE(a, 0.95) << style;
    // The vector file: the ink's strokes, exactly, over the paint.
    const std::string svg = read_file(render(style, base + ".svg"));
    EXPECT_NE(svg.find("id=\"layer-paint\""), std::string::npos) << style;
    EXPECT_EQ(without_paint(svg), ink_svg) << style;
    // rsvg-convert draws the paint under the lines as the PNG shows them.
    const RunResult r =
        run_command("rsvg-convert -w " + std::to_string(kSize) + " -h " + std::to_string(kSize) +
                    " -o " + base + "-svg.png " + base + ".svg");
    ASSERT_EQ(r.status, 0) << r.output;
    const cv::Mat drawn = cv::imread(base + "-svg.png", cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(drawn.size(), stacked.size());
    cv::Mat diff;
    cv::absdiff(drawn, stacked, diff);
    EXPECT_LT(cv::mean(diff)[0], 4.0) << style;
  }
  // Where the ink draws nothing, pen-and-wash is its paint: not the paper, not the lines.
  const cv::Mat wash = cv::imread(dir + "/pen-and-wash.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat blank = ink == 255;
  EXPECT_LT(cv::mean(wash, blank & (wash < 250))[0], 250.0);
  EXPECT_GT(cv::countNonZero(blank & (wash < 235)), kSize * kSize / 50);
}

TEST(Layers, ALaterLayerThatDrawsNoLinesIsOneLine) {
  const std::string dir = temp_dir("layers-bad");
  write_file(dir + "/bad.toml", "layers = [\"ink\", \"toon\"]\n");
  const std::string out = dir + "/x.png";
  expect_input_error("render " + small_tree() + " --size 64 --style " + dir + "/bad.toml -o " + out,
                     "every layer after the first must be a line style");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace sylva::test
