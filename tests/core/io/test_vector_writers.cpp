// SVG and PDF output of stroke drawings (core/io/svg_writer.h, core/io/pdf_writer.h), checked by
// tools nobody here wrote: xmllint finds the SVG well-formed, rsvg-convert renders it and
// pdftoppm renders the PDF to the raster ink's pixels (core/stroke_render.h); layers are named
// Inkscape layers; the page size follows the dpi; the same drawing gives the same bytes; a bad
// path or dpi is an error that leaves no file.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/io/pdf_writer.h"
#include "core/io/svg_writer.h"
#include "core/stroke_render.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

// Every kind of stroke: closed, open, tapered (filled), dots, a tone layer, half opacity, a
// filled region with a hole (the shadow layer).
StrokeDrawing drawing() {
  StrokeDrawing d;
  d.size = {160, 120};
  Stroke sil;
  sil.points = {{20, 20}, {140, 20}, {140, 100}, {20, 100}};
  sil.closed = true;
  sil.width = 3.0f;
  Stroke wood;
  wood.cls = LineClass::Wood;
  wood.points = {{40, 90}, {80, 40}, {120, 90}};
  wood.width = 1.5f;
  wood.widths = {0.5f, 4.0f, 0.5f};
  Stroke tone;
  tone.cls = LineClass::Tone;
  tone.width = 1.0f;
  tone.opacity = 0.5f;
  Stroke dot;
  dot.cls = LineClass::Tone;
  dot.points = {{100, 60}};
  dot.width = 5.0f;
  Stroke shadow;
  shadow.cls = LineClass::Shadow;
  shadow.filled = shadow.closed = true;
  shadow.points = {{100, 4}, {150, 4}, {150, 40}, {100, 40}};
  shadow.holes = {{{115, 15}, {135, 15}, {135, 30}, {115, 30}}};
  d.strokes = {shadow, dot};
  for (int i = 0; i < 6; ++i) {
    tone.points = {{30.0f + 6 * i, 70}, {40.0f + 6 * i, 50}};
    d.strokes.push_back(tone);
  }
  d.strokes.push_back(wood);
  d.strokes.push_back(sil);
  return d;
}

// Ink (0..1, 1 = full ink) of a white-background rendering.
cv::Mat ink_of(const std::string& png) {
  cv::Mat img = cv::imread(png, cv::IMREAD_GRAYSCALE);
  if (img.empty()) return img;
  cv::Mat ink;
  img.convertTo(ink, CV_32F, -1.0 / 255.0, 1.0);
  return ink;
}

// The raster ink of the same drawing, in sRGB-encoded darkness as a renderer shows it on white.
cv::Mat raster_ink(const StrokeDrawing& d) {
  return rasterize_strokes(d);
}

void expect_same_ink(const cv::Mat& got, const cv::Mat& want) {
  ASSERT_EQ(got.size(), want.size());
  cv::Mat diff;
  cv::absdiff(got, want, diff);
  // Renderers antialias edges slightly differently; the strokes themselves agree.
  EXPECT_LT(cv::mean(diff)[0], 0.02);
  EXPECT_GT(double(cv::countNonZero(diff < 0.25f)) / diff.total(), 0.99);
}

// Share of `a`'s ink pixels (ink >= 0.5) within 1.5 px of `b`'s.
double ink_near(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat dist;
  cv::distanceTransform(~cv::Mat(b >= 0.5f), dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const cv::Mat ink = a >= 0.5f;
  return double(cv::countNonZero(ink & (dist <= 1.5f))) / std::max(1, cv::countNonZero(ink));
}

// Poppler snaps strokes to whole pixels (stroke adjustment) where cairo antialiases them, so
// the PDF's pixels are compared by where the ink is, both ways.
void expect_near_ink(const cv::Mat& got, const cv::Mat& want) {
  ASSERT_EQ(got.size(), want.size());
  EXPECT_GT(ink_near(got, want), 0.98);
  EXPECT_GT(ink_near(want, got), 0.98);
}

TEST(SvgWriter, WellFormedLayersRenderedByRsvgLikeTheRaster) {
  const std::string dir = temp_dir("svg");
  const StrokeDrawing d = drawing();
  write_svg(dir + "/d.svg", d, VectorPage{});
  const RunResult lint = run_command("xmllint --noout " + dir + "/d.svg");
  EXPECT_EQ(lint.status, 0) << lint.output;
  const std::string svg = read_file(dir + "/d.svg");
  for (const char* layer : {"paper", "shadow", "silhouette", "wood", "tone"})
    EXPECT_NE(svg.find(std::string("inkscape:groupmode=\"layer\" id=\"layer-") + layer +
                       "\" inkscape:label=\"" + layer + "\""),
              std::string::npos)
        << layer;
  EXPECT_NE(svg.find("viewBox=\"0 0 160 120\""), std::string::npos);
  EXPECT_NE(svg.find("width=\"160\" height=\"120\""), std::string::npos);
  const RunResult r =
      run_command("rsvg-convert -w 160 -h 120 -b white -o " + dir + "/d.png " + dir + "/d.svg");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_same_ink(ink_of(dir + "/d.png"), raster_ink(d));
  EXPECT_EQ(svg, svg_document(d, VectorPage{}));  // same drawing, same bytes
}

TEST(SvgWriter, PhysicalSizeAndTransparentPaper) {
  VectorPage page;
  page.dpi = 254.0;  // 10 px per mm
  page.paper.reset();
  const std::string svg = svg_document(drawing(), page);
  EXPECT_NE(svg.find("width=\"16mm\" height=\"12mm\""), std::string::npos);
  EXPECT_EQ(svg.find("layer-paper"), std::string::npos);
  EXPECT_NE(svg.find("viewBox=\"0 0 160 120\""), std::string::npos);
}

TEST(PdfWriter, RenderedByPdftoppmLikeTheRaster) {
  const std::string dir = temp_dir("pdf");
  const StrokeDrawing d = drawing();
  write_pdf(dir + "/d.pdf", d, VectorPage{});
  const std::string pdf = read_file(dir + "/d.pdf");
  ASSERT_EQ(pdf.rfind("%PDF-", 0), 0u);
  EXPECT_EQ(pdf, pdf_document(d, VectorPage{}));  // same drawing, same bytes
  const RunResult r =
      run_command("pdftoppm -png -r 72 -singlefile " + dir + "/d.pdf " + dir + "/page");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_near_ink(ink_of(dir + "/page.png"), raster_ink(d));
  // At 144 dpi the page is half the size in points: 80 x 60 pt, rendered at 144 dpi back to
  // 160 x 120 px.
  VectorPage page;
  page.dpi = 144.0;
  write_pdf(dir + "/half.pdf", d, page);
  ASSERT_EQ(
      run_command("pdftoppm -png -r 144 -singlefile " + dir + "/half.pdf " + dir + "/half").status,
      0);
  expect_near_ink(ink_of(dir + "/half.png"), raster_ink(d));
}

TEST(VectorWriters, BadPathOrDpiIsAnErrorAndLeavesNothing) {
  const std::string dir = temp_dir("vector-bad");
  const StrokeDrawing d = drawing();
  EXPECT_THROW(write_svg(dir + "/missing/d.svg", d, VectorPage{}), InputError);
  EXPECT_THROW(write_pdf(dir + "/missing/d.pdf", d, VectorPage{}), InputError);
  VectorPage page;
  for (double dpi : {-1.0, 10000.5, std::nan("")}) {
    page.dpi = dpi;
    EXPECT_THROW(write_svg(dir + "/d.svg", d, page), InputError) << dpi;
    EXPECT_THROW(write_pdf(dir + "/d.pdf", d, page), InputError) << dpi;
  }
  for (double dpi : {0.0, 10000.0})
    EXPECT_NO_THROW(check_dpi(dpi, "dpi"));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace sylva::test
