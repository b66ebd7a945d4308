#include "core/strokes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace sylva {

const char* line_class_name(LineClass c) {
  switch (c) {
    case LineClass::Silhouette:
      return "silhouette";
    case LineClass::Interior:
      return "interior";
    case LineClass::Wood:
      return "wood";
    case LineClass::Detail:
      return "detail";
    case LineClass::Tone:
      return "tone";
    case LineClass::Foliage:
      return "foliage";
    case LineClass::Shadow:
      return "shadow";
  }
  return "?";
}

size_t StrokeDrawing::count(LineClass c) const {
  return static_cast<size_t>(
      std::count_if(strokes.begin(), strokes.end(), [c](const Stroke& s) { return s.cls == c; }));
}

void append_strokes(StrokeDrawing& a, const StrokeDrawing& b) {
  SYLVA_CHECK(a.size == b.size, "append_strokes: drawings of different sizes");
  a.strokes.insert(a.strokes.end(), b.strokes.begin(), b.strokes.end());
}

namespace {

struct Vertex {
  glm::vec2 p;
  float half;  // half width, px
};

// The stroke's points with their half widths, repeated points dropped (a zero-length segment
// has no direction).
std::vector<Vertex> vertices(const Stroke& s) {
  std::vector<Vertex> v;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const float half = 0.5f * (s.constant_width() ? s.width : s.widths[i]);
    if (!v.empty() && glm::distance(v.back().p, s.points[i]) < 1e-4f) {
      v.back().half = std::max(v.back().half, half);
      continue;
    }
    v.push_back({s.points[i], half});
  }
  if (s.closed && v.size() > 1 && glm::distance(v.front().p, v.back().p) < 1e-4f) v.pop_back();
  return v;
}

glm::vec2 left_normal(glm::vec2 a, glm::vec2 b) {
  const glm::vec2 d = glm::normalize(b - a);
  return {-d.y, d.x};
}

// The offset of vertex i toward the left, mitred between its two segments' normals; the mitre
// is capped at twice the half width so a hairpin does not spike.
glm::vec2 offset(const std::vector<Vertex>& v, size_t i, bool closed) {
  const size_t n = v.size();
  const bool first = i == 0 && !closed, last = i + 1 == n && !closed;
  const glm::vec2 n_in =
      first ? left_normal(v[0].p, v[1].p) : left_normal(v[(i + n - 1) % n].p, v[i].p);
  const glm::vec2 n_out = last ? n_in : left_normal(v[i].p, v[(i + 1) % n].p);
  glm::vec2 m = n_in + n_out;
  const float len = glm::length(m);
  m = len > 1e-6f ? m / len : n_out;
  const float c = std::max(0.5f, glm::dot(m, n_out));
  return m * (v[i].half / c);
}

// Half circle around p of radius r from direction `from` through `through` (unit vectors at
// right angles), excluding its start, including its end.
void half_circle(std::vector<glm::vec2>& out, glm::vec2 p, float r, glm::vec2 from,
                 glm::vec2 through, int segments) {
  for (int k = 1; k <= segments; ++k) {
    const double t = std::numbers::pi * k / segments;
    out.push_back(p + r * (float(std::cos(t)) * from + float(std::sin(t)) * through));
  }
}

}  // namespace

std::vector<std::vector<glm::vec2>> stroke_outline(const Stroke& s, int cap_segments) {
  SYLVA_CHECK(s.constant_width() || s.widths.size() == s.points.size(),
              "stroke_outline: widths and points differ in count");
  SYLVA_CHECK(cap_segments >= 2, "stroke_outline: too few cap segments");
  const std::vector<Vertex> v = vertices(s);
  if (v.empty()) return {};
  if (v.size() == 1) {  // a dot
    std::vector<glm::vec2> circle;
    half_circle(circle, v[0].p, v[0].half, {1, 0}, {0, 1}, cap_segments);
    half_circle(circle, v[0].p, v[0].half, {-1, 0}, {0, -1}, cap_segments);
    return {circle};
  }
  const size_t n = v.size();
  const bool closed = s.closed && n > 2;
  std::vector<glm::vec2> left(n), right(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::vec2 o = offset(v, i, closed);
    left[i] = v[i].p + o;
    right[i] = v[i].p - o;
  }
  if (closed) {
    std::reverse(right.begin(), right.end());
    return {left, right};
  }
  std::vector<glm::vec2> poly = left;
  const glm::vec2 d_end = glm::normalize(v[n - 1].p - v[n - 2].p);
  half_circle(poly, v[n - 1].p, v[n - 1].half, {-d_end.y, d_end.x}, d_end, cap_segments);
  poly.pop_back();  // the cap ends on right[n - 1]
  for (size_t i = n; i-- > 0;)
    poly.push_back(right[i]);
  const glm::vec2 d_start = glm::normalize(v[1].p - v[0].p);
  half_circle(poly, v[0].p, v[0].half, {d_start.y, -d_start.x}, -d_start, cap_segments);
  poly.pop_back();  // the cap ends on left[0]
  return {poly};
}

}  // namespace sylva
