// Ink composite and paper: pure pen drawing (exact white ground, exact line colour), paper
// colour, the wash of the shaded colour, seeded grain (deterministic, resolution-independent),
// transparent output, and the graph. scripts/look.sh writes a composite of analytic lines over
// a shaded disc as a PNG for a visual check.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "passes/composite.h"
#include "passes/edges.h"

namespace sylva::test {
namespace {

uint8_t encode(float lin) {
  lin = std::clamp(lin, 0.0f, 1.0f);
  const float c = lin <= 0.0031308f ? lin * 12.92f : 1.055f * std::pow(lin, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(c * 255.0f));
}

// A ramp of line coverage 0..1 along x, a shaded disc (BGRA sRGB, alpha = coverage) in the
// middle.
struct Inputs {
  cv::Mat lines, color;
};
Inputs inputs(int w = 101, int h = 60) {
  Inputs in;
  in.lines.create(h, w, CV_32FC1);
  for (int x = 0; x < w; ++x)
    in.lines.col(x).setTo(float(x) / float(w - 1));
  in.lines.rowRange(0, h / 2).setTo(0.0f);  // the top half has no lines
  in.color = cv::Mat::zeros(h, w, CV_8UC4);
  cv::circle(in.color, cv::Point(w / 2, h / 2), h / 3, cv::Scalar(40, 90, 200, 255), cv::FILLED);
  return in;
}

cv::Mat paper_for(const cv::Mat& like, const InkParams& p) {
  return make_paper(like.size(), p.paper);
}

TEST(InkComposite, PurePenDrawingIsLinesOnWhite) {
  const Inputs in = inputs();
  InkParams p;
  const cv::Mat out = composite_ink(in.lines, in.color, paper_for(in.lines, p), p);
  ASSERT_EQ(out.type(), CV_8UC4);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) {
      const float l = in.lines.at<float>(y, x);
      // Black over white blended in sRGB values, as SVG and PDF renderers do.
      const uint8_t v = uint8_t(std::lround(255.0f * (1.0f - l)));
      ASSERT_EQ(out.at<cv::Vec4b>(y, x), cv::Vec4b(v, v, v, 255)) << y << "," << x;
    }
}

TEST(InkComposite, PaperAndLineColours) {
  const Inputs in = inputs();
  InkParams p;
  ASSERT_TRUE(parse_hex_color("#f2e8d0", p.paper.color));
  ASSERT_TRUE(parse_hex_color("#203050", p.line_color));
  const cv::Mat out = composite_ink(in.lines, in.color, paper_for(in.lines, p), p);
  EXPECT_EQ(out.at<cv::Vec4b>(0, 0), cv::Vec4b(0xd0, 0xe8, 0xf2, 255));  // paper
  EXPECT_EQ(out.at<cv::Vec4b>(out.rows - 1, out.cols - 1),
            cv::Vec4b(0x50, 0x30, 0x20, 255));  // ink
}

TEST(InkComposite, FillWashesTheShadedColourUnderTheLines) {
  const Inputs in = inputs();
  InkParams p;
  const cv::Point centre(in.color.cols / 2, in.color.rows / 2 - 5);  // inside the disc, no line
  const cv::Vec4b shaded = in.color.at<cv::Vec4b>(centre);
  p.fill = 0.0f;
  EXPECT_EQ(composite_ink(in.lines, in.color, paper_for(in.lines, p), p).at<cv::Vec4b>(centre),
            cv::Vec4b(255, 255, 255, 255));
  p.fill = 1.0f;
  const cv::Mat full = composite_ink(in.lines, in.color, paper_for(in.lines, p), p);
  EXPECT_EQ(full.at<cv::Vec4b>(centre), shaded);
  EXPECT_EQ(full.at<cv::Vec4b>(0, 0), cv::Vec4b(255, 255, 255, 255));  // outside: paper
  p.fill = 0.3f;
  const cv::Vec4b light =
      composite_ink(in.lines, in.color, paper_for(in.lines, p), p).at<cv::Vec4b>(centre);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(light[k], shaded[k]);
    EXPECT_LT(light[k], 255);
  }
  // Lines stay on top of the wash.
  EXPECT_EQ(full.at<cv::Vec4b>(in.lines.rows - 1, in.lines.cols - 1), cv::Vec4b(0, 0, 0, 255));
}

TEST(InkComposite, CoverageMaskFillsFlat) {
  const Inputs in = inputs();
  cv::Mat mask;
  cv::extractChannel(in.color, mask, 3);
  mask.convertTo(mask, CV_32FC1, 1.0 / 255.0);
  InkParams p;
  p.fill = 0.5f;
  const cv::Mat out = composite_ink(in.lines, mask, paper_for(in.lines, p), p);
  const uint8_t half = encode(0.5f);  // white paper, half-way to black line colour
  EXPECT_EQ(out.at<cv::Vec4b>(in.color.rows / 2 - 5, in.color.cols / 2),
            cv::Vec4b(half, half, half, 255));
}

TEST(InkComposite, TransparentKeepsOnlyTheDrawing) {
  const Inputs in = inputs();
  InkParams p;
  p.transparent = true;
  const cv::Mat out = composite_ink(in.lines, in.color, paper_for(in.lines, p), p);
  EXPECT_EQ(out.at<cv::Vec4b>(0, 0)[3], 0);                               // no line, no coverage
  EXPECT_EQ(out.at<cv::Vec4b>(in.color.rows / 2 - 5, in.color.cols / 2),  // drawing: paper
            cv::Vec4b(255, 255, 255, 255));
  EXPECT_EQ(out.at<cv::Vec4b>(out.rows - 1, out.cols - 1), cv::Vec4b(0, 0, 0, 255));  // line
}

TEST(Paper, GrainIsSeededAndDeterministic) {
  PaperParams p;
  const cv::Size size(300, 200);
  cv::Mat flat = make_paper(size, p);
  double lo = 0, hi = 0;
  cv::minMaxLoc(flat.reshape(1), &lo, &hi);
  EXPECT_EQ(lo, 1.0);
  EXPECT_EQ(hi, 1.0);
  p.grain = 1.0f;
  const cv::Mat a = make_paper(size, p), b = make_paper(size, p);
  EXPECT_EQ(std::memcmp(a.data, b.data, a.total() * a.elemSize()), 0);
  cv::minMaxLoc(a.reshape(1), &lo, &hi);
  EXPECT_LT(lo, 0.95);
  EXPECT_GT(hi, 1.05);
  EXPECT_GE(lo, 0.75);
  EXPECT_NEAR(cv::mean(a)[0], 1.0, 0.02);
  p.seed = 2;
  const cv::Mat c = make_paper(size, p);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1) / double(a.total()), 0.01);
}

TEST(Paper, GrainLooksTheSameAtEveryResolution) {
  PaperParams p;
  p.grain = 1.0f;
  p.grain_size = 4.0f;
  const cv::Mat small = make_paper(cv::Size(512, 512), p);
  cv::Mat big;
  cv::resize(make_paper(cv::Size(2048, 2048), p), big, cv::Size(512, 512), 0, 0, cv::INTER_AREA);
  cv::Mat a, b;
  cv::extractChannel(small, a, 0);
  cv::extractChannel(big, b, 0);
  a -= cv::mean(a)[0];
  b -= cv::mean(b)[0];
  const double correlation = a.dot(b) / std::sqrt(a.dot(a) * b.dot(b));
  EXPECT_GT(correlation, 0.8);
}

TEST(InkComposite, GraphProducesTheFinalImage) {
  const Inputs in = inputs();
  RenderGraph g;
  const ImageHandle lines = g.resource<cv::Mat>("edges"), color = g.resource<cv::Mat>("color");
  g.add_pass("write-edges", {}, {lines}, [&](PassContext& c) { c.write(lines, in.lines); });
  g.add_pass("write-color", {}, {color}, [&](PassContext& c) { c.write(color, in.color); });
  InkParams p;
  p.paper.grain = 0.3f;
  const auto out = add_ink_composite_pass(g, lines, color, p, in.lines.size());
  EXPECT_EQ(g.resource_name(out), "ink");
  g.present(out);
  g.execute();
  const cv::Mat& image = g.get<cv::Mat>(out);
  const cv::Mat direct = composite_ink(in.lines, in.color, make_paper(in.lines.size(), p.paper), p);
  ASSERT_EQ(image.type(), CV_8UC4);
  EXPECT_EQ(cv::norm(image, direct, cv::NORM_INF), 0.0);
}

// A flat sheet (no grain) as one pixel composites as the whole sheet does, in every mode, and
// the pass makes it so; a one-pixel-wide frame too.
TEST(InkComposite, AFlatSheetAsOnePixelCompositesAsTheWholeSheet) {
  for (const cv::Size size : {cv::Size(101, 60), cv::Size(1, 7)}) {
    Inputs in = inputs(size.width, size.height);
    if (size.width == 1) in.lines.setTo(0.5f);  // the ramp needs two columns
    InkParams p;
    p.paper.color = glm::vec3(0.9f, 0.8f, 0.6f);
    for (const float fill : {0.0f, 0.5f})
      for (const bool transparent : {false, true}) {
        p.fill = fill;
        p.transparent = transparent;
        const cv::Mat whole = composite_ink(in.lines, in.color, make_paper(size, p.paper), p);
        const cv::Mat one = composite_ink(in.lines, in.color, make_paper({1, 1}, p.paper), p);
        EXPECT_EQ(cv::norm(whole, one, cv::NORM_INF), 0.0) << size << fill << transparent;
      }
    RenderGraph g;
    const ImageHandle lines = g.resource<cv::Mat>("edges"), color = g.resource<cv::Mat>("color");
    g.add_pass("write-edges", {}, {lines}, [&](PassContext& c) { c.write(lines, in.lines); });
    g.add_pass("write-color", {}, {color}, [&](PassContext& c) { c.write(color, in.color); });
    const auto out = add_ink_composite_pass(g, lines, color, p, size);
    g.present(out);
    g.execute();
    const cv::Mat direct = composite_ink(in.lines, in.color, make_paper(size, p.paper), p);
    EXPECT_EQ(cv::norm(g.get<cv::Mat>(out), direct, cv::NORM_INF), 0.0) << size;
  }
}

}  // namespace
}  // namespace sylva::test
