// Strokes (DESIGN.md §6): the one representation of a line drawing. A stroke is a polyline in
// image coordinates with a class, a width (constant, or one per point for tapered and
// depth-varying strokes) and an opacity; a drawing is the strokes of one image in drawing
// order, all in one ink colour. The raster ink (core/stroke_render.h), the SVG and the PDF are
// all drawn from it, so they agree by construction.
//
// Coordinates are continuous image coordinates in px: x to the right, y down, pixel (i, j)
// covering [i, i + 1) x [j, j + 1) (its centre at (i + 0.5, j + 0.5)), as in cairo and SVG.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace sylva {

// The line hierarchy (issue "Ink for illustrators"): the plant's outer silhouette, interior
// crown contours (one part of the crown in front of another), wood (trunk and branch
// outlines), leaf-level detail, tone (hatching or stippling), the foliage's drawing primitives
// (Deussen & Strothotte's leaf outlines, passes/leaf_primitives.h) and shadow (the black
// masses of the deep shadow, filled regions).
enum class LineClass : uint8_t {
  Silhouette = 0,
  Interior = 1,
  Wood = 2,
  Detail = 3,
  Tone = 4,
  Foliage = 5,
  Shadow = 6
};
inline constexpr int kLineClassCount = 7;
// "silhouette", "interior", "wood", "detail", "tone", "foliage", "shadow"
const char* line_class_name(LineClass c);

struct Stroke {
  std::vector<glm::vec2> points;  // px; one point = a dot
  // px per point (same size as points), or empty: every point `width` wide.
  std::vector<float> widths;
  float width = 1.0f;    // px, > 0, when widths is empty
  float opacity = 1.0f;  // [0, 1]
  LineClass cls = LineClass::Silhouette;
  bool closed = false;  // the last point joins the first
  // A filled region rather than a line: `points` is its outer ring (closed) and `holes` the
  // rings cut out of it, filled by the even-odd rule; widths and width are not used.
  bool filled = false;
  std::vector<std::vector<glm::vec2>> holes;
  bool constant_width() const { return widths.empty(); }
};

struct StrokeDrawing {
  cv::Size size;                      // the image the strokes are drawn on, px
  glm::vec3 color{0.0f, 0.0f, 0.0f};  // linear RGB of the ink
  std::vector<Stroke> strokes;        // in drawing order
  // The paint under the strokes (a stacked preset's paint layer, styles/style.h): CV_8UC4 BGRA
  // sRGB, straight alpha, `size`; empty = none. Vector files carry it as an image under the
  // lines.
  cv::Mat paint;
  size_t count(LineClass c) const;
};

// The filled outline of a stroke with per-point widths: the polyline offset by half the width
// to either side (mitred, the mitre capped at twice the half width), with round ends of
// `cap_segments` segments per half circle (open strokes). An open stroke gives one closed
// polygon; a closed stroke two (outer and inner, the inner reversed, so the ring fills under
// the non-zero rule). A constant-width stroke is outlined with its `width` at every point.
std::vector<std::vector<glm::vec2>> stroke_outline(const Stroke& s, int cap_segments = 8);

// Joins open strokes of one class and opacity whose ends meet (within `reach` px) into longer
// strokes, so a run of short arcs along an outline becomes one path; a chain whose ends meet is
// closed. Widths become per point where the joined strokes' differ. Greedy and deterministic
// (strokes in order, each extended by the nearest free end, ties to the lower index); filled
// regions and closed strokes are left as they are.
void chain_strokes(std::vector<Stroke>& strokes, float reach);

// Appends b's strokes to a (same size; a's colour is kept).
void append_strokes(StrokeDrawing& a, const StrokeDrawing& b);

}  // namespace sylva
