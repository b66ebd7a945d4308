#include "core/stroke_render.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

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

// A stroke rasterize_strokes covers itself (line_coverage) rather than through cairo: a line of
// one width, or tapered (a width per point). Cairo strokes these exactly but slowly (its stroker
// and scan converter cost about 1 µs per point); a branch's thousands of hairlines are the ink
// frame's longest pass with it.
bool covered_as_line(const Stroke& s) {
  return !s.filled && s.points.size() > 1 &&
         (s.constant_width() || s.widths.size() == s.points.size());
}

// Paints d's strokes (those covered_as_line too where `lines`) whose rows can reach
// [row_lo, row_hi]: their stroke_rows, in `rows` when given (one per stroke).
void paint(cairo_t* cr, const StrokeDrawing& d, double scale, float row_lo, float row_hi,
           bool lines, const std::vector<std::pair<float, float>>* rows = nullptr) {
  const double r = linear_to_srgb(d.color.r), g = linear_to_srgb(d.color.g),
               b = linear_to_srgb(d.color.b);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_WINDING);
  for (size_t i = 0; i < d.strokes.size(); ++i) {
    const Stroke& s = d.strokes[i];
    if (s.points.empty() || s.opacity <= 0.0f || (!lines && covered_as_line(s))) continue;
    if (row_lo > -kNoCull) {
      const auto [lo, hi] = rows ? (*rows)[i] : stroke_rows(s);
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

// The share of a pixel at distance `dist` px from a line's axis that the line, `half` px to
// either side of its axis, covers: the overlap of [-half, half] with the pixel's extent across
// the line, [dist - 0.5, dist + 0.5] (exact for a long line along a pixel row, within a few
// per cent at any angle).
float cross_coverage(float dist, float half) {
  return std::clamp(std::min(half, dist + 0.5f) - std::max(-half, dist - 0.5f), 0.0f, 1.0f);
}

// The pixels a box [lo, hi] touches along one axis, within [0, n): [first, end).
std::pair<int, int> pixel_span(float lo, float hi, int n) {
  const float a = std::clamp(std::floor(lo), 0.0f, float(n)),
              b = std::clamp(std::ceil(hi), 0.0f, float(n));
  return {int(a), int(b)};
}

// A line's own coverage over its box: `cols` x `rows` pixels, row-major, its pixel (0, 0) the
// frame's `origin`. Plain memory: a frame's thousands of short lines each clear and composite
// one, and an image's per-call costs would outweigh their few pixels.
struct Patch {
  float* px = nullptr;
  int cols = 0, rows = 0;
  cv::Point origin;
};

// The coverage of the segment [a, b], its half width `half_a` at a and `half_b` at b and
// between them as far along as a pixel's nearest point, kept in `cover` where it is more than
// `cover` holds.
void cover_segment(Patch& cover, glm::vec2 a, glm::vec2 b, float half_a, float half_b) {
  // A pixel is covered only when its centre is nearer than `most` + 1/2 to the segment.
  const float most = std::max(half_a, half_b), reach = most + 0.5f;
  const glm::vec2 o(cover.origin.x, cover.origin.y), lo = glm::min(a, b) - reach - o,
                                                     hi = glm::max(a, b) + reach - o;
  const auto [x0, x1] = pixel_span(lo.x, hi.x, cover.cols);
  const auto [y0, y1] = pixel_span(lo.y, hi.y, cover.rows);
  const glm::vec2 ab = b - a;
  const float len2 = glm::dot(ab, ab), inv = len2 > 1e-12f ? 1.0f / len2 : 0.0f;
  const float far2 = (most + 0.5f) * (most + 0.5f);  // no coverage from this squared distance
  const float taper = half_b - half_a;
  for (int y = y0; y < y1; ++y) {
    float* row = cover.px + size_t(y) * size_t(cover.cols);
    const float py = float(cover.origin.y + y) + 0.5f - a.y;
    for (int x = x0; x < x1; ++x) {
      const float px = float(cover.origin.x + x) + 0.5f - a.x;
      const float t = std::clamp((px * ab.x + py * ab.y) * inv, 0.0f, 1.0f);
      const float ex = px - t * ab.x, ey = py - t * ab.y, d2 = ex * ex + ey * ey;
      if (d2 < far2) row[x] = std::max(row[x], cross_coverage(std::sqrt(d2), half_a + t * taper));
    }
  }
}

// A line's points' extent grown by its half width and half a pixel: what it can
// touch. Not drawn when a point or the width is not finite, or the opacity is nothing.
struct LineBox {
  glm::vec2 lo{0.0f}, hi{0.0f};
  bool drawn = false;
};

LineBox line_box(const Stroke& s) {
  float width = s.width;
  for (float w : s.widths)
    width = std::isfinite(w) ? std::max(width, w) : w;
  const float reach = 0.5f * width + 0.5f;
  LineBox box{s.points[0], s.points[0], std::isfinite(reach) && s.opacity > 0.0f};
  for (const glm::vec2& q : s.points) {
    box.lo = glm::min(box.lo, q);
    box.hi = glm::max(box.hi, q);
    box.drawn = box.drawn && std::isfinite(q.x) && std::isfinite(q.y);
  }
  box.lo -= reach;
  box.hi += reach;
  return box;
}

// Composites a line stroke (covered_as_line, its line_box `box`) over `coverage`'s rows
// [rows.start, rows.end) (coverage += c (1 - coverage), c its coverage times its opacity, as
// cairo's OVER): each pixel covered as by its nearest segment, so the line's joins and ends are
// round, as cairo's. `scratch` holds the stroke's own coverage over its box.
void cover_line(cv::Mat& coverage, const Stroke& s, const LineBox& box, cv::Range rows,
                std::vector<float>& scratch) {
  const float opacity = std::min(s.opacity, 1.0f);
  const auto [x0, x1] = pixel_span(box.lo.x, box.hi.x, coverage.cols);
  const auto [y0, y1] = pixel_span(std::max(box.lo.y, float(rows.start)),
                                   std::min(box.hi.y, float(rows.end)), coverage.rows);
  if (x0 >= x1 || y0 >= y1) return;
  const size_t area = size_t(y1 - y0) * size_t(x1 - x0);
  if (scratch.size() < area) scratch.resize(area);
  std::fill_n(scratch.begin(), area, 0.0f);
  Patch patch{scratch.data(), x1 - x0, y1 - y0, {x0, y0}};
  const size_t n = s.points.size();
  auto half = [&](size_t i) { return 0.5f * (s.constant_width() ? s.width : s.widths[i]); };
  for (size_t i = 0; i + 1 < n + (s.closed ? 1 : 0); ++i)
    cover_segment(patch, s.points[i], s.points[(i + 1) % n], half(i), half((i + 1) % n));
  for (int y = y0; y < y1; ++y) {
    float* dst = coverage.ptr<float>(y) + x0;
    const float* src = patch.px + size_t(y - y0) * size_t(patch.cols);
    for (int x = 0; x < patch.cols; ++x)
      dst[x] += src[x] * opacity * (1.0f - dst[x]);
  }
}

// Paints the strokes cairo draws (all but the lines) reaching rows [y0, y1) on those rows of
// `alpha` (CV_8UC1, cairo's A8 stride). False when cairo cannot make the surface.
bool paint_band(cv::Mat& alpha, const StrokeDrawing& d, int y0, int y1,
                const std::vector<std::pair<float, float>>& rows) {
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create_for_data(alpha.ptr(y0), CAIRO_FORMAT_A8, d.size.width, y1 - y0,
                                          int(alpha.step[0])),
      &cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) return false;
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()),
                                                        &cairo_destroy);
  cairo_translate(cr.get(), 0.0, -double(y0));
  paint(cr.get(), d, 1.0, float(y0), float(y1), false, &rows);
  cairo_surface_flush(surface.get());
  return true;
}

}  // namespace

void paint_strokes(cairo_t* cr, const StrokeDrawing& d, double scale) {
  paint(cr, d, scale, -kNoCull, kNoCull, true);
}

namespace {

// Where each stroke can reach, found once for every band: the lines' boxes, the other strokes'
// rows (for cairo), and whether there is any stroke for cairo to paint.
struct StrokeReach {
  std::vector<LineBox> boxes;
  std::vector<std::pair<float, float>> rows;
  bool cairo = false;
};

StrokeReach stroke_reach(const StrokeDrawing& d) {
  StrokeReach r;
  r.boxes.resize(d.strokes.size());
  r.rows.assign(d.strokes.size(), {0.0f, 0.0f});
  for (size_t i = 0; i < d.strokes.size(); ++i) {
    const Stroke& s = d.strokes[i];
    if (covered_as_line(s)) {
      r.boxes[i] = line_box(s);
    } else if (!s.points.empty() && s.opacity > 0.0f) {
      r.rows[i] = stroke_rows(s);
      r.cairo = true;
    }
  }
  return r;
}

}  // namespace

cv::Mat rasterize_strokes(const StrokeDrawing& d) {
  SYLVA_CHECK(d.size.width > 0 && d.size.height > 0, "rasterize_strokes: empty size");
  const int stride = cairo_format_stride_for_width(CAIRO_FORMAT_A8, d.size.width);
  SYLVA_CHECK(stride > 0, "rasterize_strokes: the image is too wide");
  const StrokeReach reach = stroke_reach(d);
  // Cleared by the bands that paint it.
  cv::Mat alpha = reach.cairo ? cv::Mat(d.size.height, stride, CV_8UC1) : cv::Mat();
  cv::Mat coverage(d.size, CV_32F);
  // Bands of rows painted in parallel, each a cairo surface over its rows of `alpha` that draws
  // the strokes reaching it (the same pixels, at the same integer offsets, as one surface
  // gives), then the lines covered over them.
  const int bands = std::clamp(d.size.height / kBandRows, 1, std::max(1, 2 * cv::getNumThreads()));
  bool ok = true;
  cv::parallel_for_(cv::Range(0, bands), [&](const cv::Range& r) {
    std::vector<float> scratch;
    for (int b = r.start; b < r.end; ++b) {
      const int y0 = d.size.height * b / bands, y1 = d.size.height * (b + 1) / bands;
      if (!reach.cairo) {
        coverage.rowRange(y0, y1).setTo(0.0f);
      } else {
        alpha.rowRange(y0, y1).setTo(0);
        if (!paint_band(alpha, d, y0, y1, reach.rows)) ok = false;
        alpha.rowRange(y0, y1)
            .colRange(0, d.size.width)
            .convertTo(coverage.rowRange(y0, y1), CV_32F, 1.0 / 255.0);
      }
      for (size_t i = 0; i < d.strokes.size(); ++i) {
        const LineBox& box = reach.boxes[i];
        if (box.drawn && box.hi.y >= float(y0) && box.lo.y <= float(y1))
          cover_line(coverage, d.strokes[i], box, {y0, y1}, scratch);
      }
    }
  });
  SYLVA_CHECK(ok, "rasterize_strokes: cannot create the surface");
  return coverage;
}

}  // namespace sylva
