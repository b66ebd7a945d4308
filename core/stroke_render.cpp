#include "core/stroke_render.h"

#include <cairo.h>

#include <memory>

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

}  // namespace

void paint_strokes(cairo_t* cr, const StrokeDrawing& d, double scale) {
  const double r = linear_to_srgb(d.color.r), g = linear_to_srgb(d.color.g),
               b = linear_to_srgb(d.color.b);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
  for (const Stroke& s : d.strokes) {
    if (s.points.empty() || s.opacity <= 0.0f) continue;
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

cv::Mat rasterize_strokes(const StrokeDrawing& d) {
  SYLVA_CHECK(d.size.width > 0 && d.size.height > 0, "rasterize_strokes: empty size");
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_A8, d.size.width, d.size.height),
      &cairo_surface_destroy);
  SYLVA_CHECK(cairo_surface_status(surface.get()) == CAIRO_STATUS_SUCCESS,
              "rasterize_strokes: cannot allocate the surface");
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                        &cairo_destroy);
  paint_strokes(cr.get(), d);
  cairo_surface_flush(surface.get());
  const cv::Mat alpha(d.size, CV_8UC1, cairo_image_surface_get_data(surface.get()),
                      static_cast<size_t>(cairo_image_surface_get_stride(surface.get())));
  cv::Mat coverage;
  alpha.convertTo(coverage, CV_32F, 1.0 / 255.0);
  return coverage;
}

}  // namespace sylva
