#include "core/stroke_render.h"

#include <cairo.h>

#include <algorithm>
#include <memory>
#include <utility>

#include "core/color.h"
#include "core/error.h"

namespace sylva {

namespace {

void trace_polyline(cairo_t* cr, const std::vector<glm::vec2>& pts, bool closed, double scale) {
  cairo_move_to(cr, pts[0].x * scale, pts[0].y * scale);
  for (size_t i = 1; i < pts.size(); ++i)
    cairo_line_to(cr, pts[i].x * scale, pts[i].y * scale);
  if (closed) cairo_close_path(cr);
}

// The least rows of a band of rasterize_strokes.
constexpr int kBandRows = 64;

// Rows beyond this are never culled (paint_strokes draws everything).
constexpr float kNoCull = 1e30f;

// The rows [lo, hi) a stroke can touch: its points' extent grown by its widest width (round
// caps and joins reach half of it, the outline's capped mitres all of it) and a pixel of
// antialiasing.
std::pair<float, float> stroke_rows(const Stroke& s) {
  float lo = s.points[0].y, hi = s.points[0].y;
  for (const glm::vec2& q : s.points) {
    lo = std::min(lo, q.y);
    hi = std::max(hi, q.y);
  }
  float width = s.width;
  for (float w : s.widths)
    width = std::max(width, w);
  const float reach = s.filled ? 1.0f : width + 1.0f;
  return {lo - reach, hi + reach};
}

void paint(cairo_t* cr, const StrokeDrawing& d, double scale, float row_lo, float row_hi) {
  const double r = linear_to_srgb(d.color.r), g = linear_to_srgb(d.color.g),
               b = linear_to_srgb(d.color.b);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
  for (const Stroke& s : d.strokes) {
    if (s.points.empty() || s.opacity <= 0.0f) continue;
    if (row_lo > -kNoCull) {
      const auto [lo, hi] = stroke_rows(s);
      if (hi < row_lo || lo > row_hi) continue;
    }
    cairo_set_source_rgba(cr, r, g, b, s.opacity);
    if (s.filled) {
      trace_polyline(cr, s.points, true, scale);
      for (const std::vector<glm::vec2>& hole : s.holes)
        if (!hole.empty()) trace_polyline(cr, hole, true, scale);
      cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
      cairo_fill(cr);
      cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
      continue;
    }
    if (s.constant_width() && s.points.size() > 1) {
      trace_polyline(cr, s.points, s.closed, scale);
      cairo_set_line_width(cr, s.width * scale);
      cairo_stroke(cr);
      continue;
    }
    for (const std::vector<glm::vec2>& ring : stroke_outline(s))
      trace_polyline(cr, ring, true, scale);
    cairo_fill(cr);
  }
  cairo_new_path(cr);
}

}  // namespace

void paint_strokes(cairo_t* cr, const StrokeDrawing& d, double scale) {
  paint(cr, d, scale, -kNoCull, kNoCull);
}

cv::Mat rasterize_strokes(const StrokeDrawing& d) {
  SYLVA_CHECK(d.size.width > 0 && d.size.height > 0, "rasterize_strokes: empty size");
  const int stride = cairo_format_stride_for_width(CAIRO_FORMAT_A8, d.size.width);
  SYLVA_CHECK(stride > 0, "rasterize_strokes: the image is too wide");
  cv::Mat alpha(d.size.height, stride, CV_8UC1, cv::Scalar(0));
  // Bands of rows painted in parallel, each a cairo surface over its rows of `alpha` that draws
  // the strokes reaching it: the same pixels, at the same integer offsets, as one surface
  // gives.
  const int bands = std::clamp(d.size.height / kBandRows, 1, std::max(1, 2 * cv::getNumThreads()));
  bool ok = true;
  cv::parallel_for_(cv::Range(0, bands), [&](const cv::Range& r) {
    for (int b = r.start; b < r.end; ++b) {
      const int y0 = d.size.height * b / bands, y1 = d.size.height * (b + 1) / bands;
      std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
          cairo_image_surface_create_for_data(alpha.ptr(y0), CAIRO_FORMAT_A8, d.size.width, y1 - y0,
                                              stride),
          &cairo_surface_destroy);
      if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
        ok = false;
        continue;
      }
      std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                            &cairo_destroy);
      cairo_translate(cr.get(), 0.0, -double(y0));
      paint(cr.get(), d, 1.0, float(y0), float(y1));
      cairo_surface_flush(surface.get());
    }
  });
  SYLVA_CHECK(ok, "rasterize_strokes: cannot create the surface");
  cv::Mat coverage;
  alpha.colRange(0, d.size.width).convertTo(coverage, CV_32F, 1.0 / 255.0);
  return coverage;
}

}  // namespace sylva
