#include "core/strokes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <unordered_map>

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

// The ends of the open strokes, in cells of `reach` px, to find the ends near a point.
class EndGrid {
 public:
  EndGrid(const std::vector<Stroke>& strokes, float reach) : m_strokes(strokes), m_reach(reach) {
    for (size_t i = 0; i < strokes.size(); ++i)
      if (joinable(strokes[i]))
        for (int end = 0; end < 2; ++end)
          m_cells[key(point(i, end))].push_back({i, end});
  }
  static bool joinable(const Stroke& s) { return !s.filled && !s.closed && s.points.size() >= 2; }
  glm::vec2 point(size_t i, int end) const {
    return end == 0 ? m_strokes[i].points.front() : m_strokes[i].points.back();
  }
  // The free end nearest to p within reach of a stroke like `like` (not `self`): (index, end),
  // or index = npos.
  std::pair<size_t, int> nearest(glm::vec2 p, size_t self, const std::vector<char>& used) const {
    std::pair<size_t, int> best{std::string::npos, 0};
    float best_d = m_reach;
    const auto [cx, cy] = cell(p);
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dx = -1; dx <= 1; ++dx) {
        const auto it = m_cells.find(pack(cx + dx, cy + dy));
        if (it == m_cells.end()) continue;
        for (const auto& [j, end] : it->second) {
          if (j == self || used[j] || !alike(m_strokes[self], m_strokes[j])) continue;
          const float d = glm::length(point(j, end) - p);
          if (d < best_d || (d == best_d && j < best.first)) best = {j, end}, best_d = d;
        }
      }
    return best;
  }

 private:
  static bool alike(const Stroke& a, const Stroke& b) {
    return a.cls == b.cls && a.opacity == b.opacity;
  }
  std::pair<int64_t, int64_t> cell(glm::vec2 p) const {
    return {int64_t(std::floor(p.x / m_reach)), int64_t(std::floor(p.y / m_reach))};
  }
  static uint64_t pack(int64_t x, int64_t y) { return (uint64_t(x) << 32) ^ uint64_t(uint32_t(y)); }
  uint64_t key(glm::vec2 p) const {
    const auto [x, y] = cell(p);
    return pack(x, y);
  }
  const std::vector<Stroke>& m_strokes;
  float m_reach;
  std::unordered_map<uint64_t, std::vector<std::pair<size_t, int>>> m_cells;
};

// Appends `b` (reversed when `flip`) to the end of `a`, its first point replacing a's last.
void append_stroke(Stroke& a, const Stroke& b, bool flip) {
  const bool per_point = !a.widths.empty() || !b.widths.empty() || a.width != b.width;
  if (per_point && a.widths.empty()) a.widths.assign(a.points.size(), a.width);
  std::vector<float> bw =
      b.widths.empty() ? std::vector<float>(b.points.size(), b.width) : b.widths;
  std::vector<glm::vec2> bp = b.points;
  if (flip) {
    std::reverse(bp.begin(), bp.end());
    std::reverse(bw.begin(), bw.end());
  }
  a.points.pop_back();
  if (per_point) a.widths.pop_back();
  a.points.insert(a.points.end(), bp.begin(), bp.end());
  if (per_point) a.widths.insert(a.widths.end(), bw.begin(), bw.end());
}

void reverse_stroke(Stroke& s) {
  std::reverse(s.points.begin(), s.points.end());
  std::reverse(s.widths.begin(), s.widths.end());
}

}  // namespace

void chain_strokes(std::vector<Stroke>& strokes, float reach) {
  if (!(reach > 0.0f)) return;
  const EndGrid grid(strokes, reach);
  std::vector<char> used(strokes.size(), 0);
  std::vector<Stroke> out;
  out.reserve(strokes.size());
  for (size_t i = 0; i < strokes.size(); ++i) {
    if (used[i]) continue;
    used[i] = 1;
    Stroke s = strokes[i];
    if (EndGrid::joinable(s)) {
      // Extend the tail, then (reversed) the head.
      for (int side = 0; side < 2; ++side) {
        for (;;) {
          const auto [j, end] = grid.nearest(s.points.back(), i, used);
          if (j == std::string::npos) break;
          used[j] = 1;
          append_stroke(s, strokes[j], end == 1);
        }
        reverse_stroke(s);
      }
      if (s.points.size() > 2 && glm::length(s.points.front() - s.points.back()) < reach) {
        s.points.pop_back();
        if (!s.widths.empty()) s.widths.pop_back();
        s.closed = true;
      }
    }
    out.push_back(std::move(s));
  }
  strokes = std::move(out);
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
