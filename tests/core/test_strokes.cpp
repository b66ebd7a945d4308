// Strokes (core/strokes.h) and their raster (core/stroke_render.h): a stroke's outline is as
// wide as the stroke with round ends, a closed stroke's is a ring, a dot is a circle; the
// raster covers a line's width, honours the opacity and gives the same bytes twice; the lines it
// covers itself agree with cairo's stroking of them (the PDF's routine).
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/stroke_render.h"
#include "core/strokes.h"

namespace sylva::test {
namespace {

Stroke line(glm::vec2 a, glm::vec2 b, float width) {
  Stroke s;
  s.points = {a, b};
  s.width = width;
  return s;
}

double polygon_area(const std::vector<glm::vec2>& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const glm::vec2& u = p[i];
    const glm::vec2& v = p[(i + 1) % p.size()];
    a += double(u.x) * v.y - double(v.x) * u.y;
  }
  return 0.5 * a;
}

TEST(StrokeOutline, AnOpenStrokeIsARectangleWithRoundEnds) {
  const auto rings = stroke_outline(line({10, 10}, {30, 10}, 4.0f), 32);
  ASSERT_EQ(rings.size(), 1u);
  // 20 x 4 plus a disc of radius 2.
  EXPECT_NEAR(std::abs(polygon_area(rings[0])), 80.0 + 3.14159 * 4.0, 0.5);
  for (const glm::vec2& p : rings[0]) {
    const float d = p.x < 10 ? glm::distance(p, {10, 10})
                             : (p.x > 30 ? glm::distance(p, {30, 10}) : std::abs(p.y - 10));
    EXPECT_NEAR(d, 2.0f, 1e-3f);
  }
}

TEST(StrokeOutline, PerPointWidthsAndClosedRingsAndDots) {
  Stroke taper = line({0, 0}, {10, 0}, 1.0f);
  taper.widths = {0.0f, 4.0f};
  const auto t = stroke_outline(taper, 16);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(std::abs(polygon_area(t[0])), 20.0 + 3.14159 * 2.0, 0.3);  // a wedge and a cap
  Stroke square;
  square.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  square.closed = true;
  square.width = 2.0f;
  const auto ring = stroke_outline(square);
  ASSERT_EQ(ring.size(), 2u);  // outer and inner, opposite windings
  EXPECT_NEAR(std::abs(polygon_area(ring[0]) + polygon_area(ring[1])), 12.0 * 12.0 - 8.0 * 8.0,
              1e-3);
  Stroke dot;
  dot.points = {{5, 5}};
  dot.width = 6.0f;
  const auto circle = stroke_outline(dot, 64);
  ASSERT_EQ(circle.size(), 1u);
  EXPECT_NEAR(std::abs(polygon_area(circle[0])), 3.14159 * 9.0, 0.1);
  EXPECT_TRUE(stroke_outline(Stroke{}).empty());
}

TEST(StrokeRaster, ALineCoversItsWidthAtItsOpacity) {
  StrokeDrawing d;
  d.size = {64, 32};
  d.strokes = {line({8, 16}, {56, 16}, 4.0f)};
  const cv::Mat c = rasterize_strokes(d);
  ASSERT_EQ(c.type(), CV_32FC1);
  EXPECT_NEAR(cv::sum(c)[0], 48.0 * 4.0 + 3.14159 * 4.0, 2.0);
  EXPECT_FLOAT_EQ(c.at<float>(15, 30), 1.0f);
  EXPECT_FLOAT_EQ(c.at<float>(12, 30), 0.0f);
  d.strokes[0].opacity = 0.5f;
  EXPECT_NEAR(rasterize_strokes(d).at<float>(15, 30), 0.5f, 1.0f / 255);
  // A tapered stroke and a dot are filled outlines; the bytes repeat.
  Stroke t = line({8, 8}, {56, 8}, 1.0f);
  t.widths = {0.5f, 3.0f};
  Stroke dot;
  dot.points = {{30, 26}};
  dot.width = 3.0f;
  d.strokes = {t, dot};
  const cv::Mat a = rasterize_strokes(d), b = rasterize_strokes(d);
  EXPECT_EQ(cv::countNonZero(a != b), 0);
  EXPECT_GT(a.at<float>(26, 30), 0.9f);
  EXPECT_GT(a.at<float>(8, 50), a.at<float>(9, 12) - 1e-6f);
}

// The drawing painted by cairo alone (paint_strokes, as the PDF is): coverage in [0, 1].
cv::Mat cairo_coverage(const StrokeDrawing& d) {
  const int stride = cairo_format_stride_for_width(CAIRO_FORMAT_A8, d.size.width);
  cv::Mat a8(d.size.height, stride, CV_8UC1, cv::Scalar(0));
  cairo_surface_t* surface = cairo_image_surface_create_for_data(
      a8.data, CAIRO_FORMAT_A8, d.size.width, d.size.height, stride);
  cairo_t* cr = cairo_create(surface);
  paint_strokes(cr, d);
  cairo_destroy(cr);
  cairo_surface_flush(surface);
  cairo_surface_destroy(surface);
  cv::Mat coverage;
  a8.colRange(0, d.size.width).convertTo(coverage, CV_32F, 1.0 / 255.0);
  return coverage;
}

TEST(StrokeRaster, LinesAreCoveredAsCairoStrokesThem) {
  // Lines of one width each, 0.25 to 4 px, open and closed, at every angle, some half opaque,
  // crossing each other: rasterize_strokes covers them itself, cairo strokes them exactly.
  StrokeDrawing d;
  d.size = {200, 150};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(5.0f, 195.0f), y(5.0f, 145.0f), w(0.25f, 4.0f);
  for (int i = 0; i < 80; ++i) {
    Stroke s;
    s.width = w(rng);
    s.opacity = i % 3 == 0 ? 0.5f : 1.0f;
    s.closed = i % 7 == 0;
    glm::vec2 at(x(rng), y(rng));
    for (int k = 0; k < 2 + i % 5; ++k) {
      s.points.push_back(at);
      at += glm::vec2(std::cos(0.9f * float(k + i)), std::sin(0.9f * float(k + i))) * 9.0f;
    }
    d.strokes.push_back(s);
  }
  const cv::Mat ours = rasterize_strokes(d), theirs = cairo_coverage(d);
  const double ink = cv::sum(theirs)[0];
  EXPECT_NEAR(cv::sum(ours)[0], ink, 0.01 * ink);
  cv::Mat diff;
  cv::absdiff(ours, theirs, diff);
  const cv::Mat inked = (ours > 0.02f) | (theirs > 0.02f);
  EXPECT_LT(cv::mean(diff, inked)[0], 0.03);
  EXPECT_LT(cv::countNonZero(diff > 0.25f), 0.005 * cv::countNonZero(inked));
  // A thin line's coverage is its width: a 0.5 px line along a row covers half a pixel.
  d.strokes = {line({10, 20.5f}, {60, 20.5f}, 0.5f)};
  EXPECT_NEAR(rasterize_strokes(d).at<float>(20, 30), 0.5f, 1e-4f);
}

TEST(StrokeRaster, ALineWithANonFinitePointOrTooMuchOpacityStaysInRange) {
  StrokeDrawing d;
  d.size = {64, 32};
  Stroke bad = line({8, 16}, {56, 16}, 2.0f);
  bad.points.push_back({std::numeric_limits<float>::quiet_NaN(), 3.0f});
  d.strokes = {bad};
  EXPECT_EQ(cv::countNonZero(rasterize_strokes(d)), 0);  // not drawn
  Stroke strong = line({8, 16}, {56, 16}, 4.0f);
  strong.opacity = 3.0f;
  d.strokes = {strong, strong};
  double lo = 0, hi = 0;
  cv::minMaxLoc(rasterize_strokes(d), &lo, &hi);
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 1.0);
}

TEST(StrokeDrawing, CountsAndAppendsByClass) {
  StrokeDrawing a, b;
  a.size = b.size = {8, 8};
  a.strokes = {line({0, 0}, {1, 1}, 1)};
  Stroke tone = line({0, 0}, {2, 2}, 1);
  tone.cls = LineClass::Tone;
  b.strokes = {tone, tone};
  append_strokes(a, b);
  EXPECT_EQ(a.count(LineClass::Silhouette), 1u);
  EXPECT_EQ(a.count(LineClass::Tone), 2u);
  EXPECT_STREQ(line_class_name(LineClass::Interior), "interior");
}

}  // namespace
}  // namespace sylva::test

namespace sylva::test {
namespace {

TEST(StrokeRaster, AFilledRegionCoversItsRingButItsHoles) {
  StrokeDrawing d;
  d.size = {64, 64};
  Stroke s;
  s.cls = LineClass::Shadow;
  s.filled = true;
  s.closed = true;
  s.points = {{8, 8}, {56, 8}, {56, 56}, {8, 56}};
  s.holes = {{{24, 24}, {40, 24}, {40, 40}, {24, 40}}};
  d.strokes.push_back(s);
  const cv::Mat c = rasterize_strokes(d);
  EXPECT_FLOAT_EQ(c.at<float>(12, 12), 1.0f);  // in the ring
  EXPECT_FLOAT_EQ(c.at<float>(32, 32), 0.0f);  // in the hole
  EXPECT_FLOAT_EQ(c.at<float>(2, 2), 0.0f);    // outside
  // The covered area is the ring's less the hole's: 48² - 16² px.
  EXPECT_NEAR(cv::sum(c)[0], 48.0 * 48.0 - 16.0 * 16.0, 1.0);
  EXPECT_STREQ(line_class_name(LineClass::Shadow), "shadow");
  EXPECT_STREQ(line_class_name(LineClass::Foliage), "foliage");
}

}  // namespace
}  // namespace sylva::test
