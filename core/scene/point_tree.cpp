#include "core/scene/point_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace sylva {

namespace {

constexpr uint32_t kLeafPoints = 16;

// A bound padded above by more than the rounding of a float result could add.
double padded(double b) {
  return b + 1e-6 * std::abs(b) + 1e-30;
}

std::array<glm::dvec3, 8> moved_corners(const glm::dmat4& t, const glm::vec3& lo,
                                        const glm::vec3& hi) {
  std::array<glm::dvec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    c[size_t(i)] = glm::dvec3(t * glm::dvec4(p, 1.0));
  }
  return c;
}

glm::vec3 moved(const glm::dmat4& t, const glm::vec3& p) {
  return glm::vec3(t * glm::dvec4(p, 1.0));
}

}  // namespace

PointTree::PointTree(std::vector<glm::vec3> points) : m_points(std::move(points)) {
  if (!m_points.empty()) build(0, uint32_t(m_points.size()));
}

int32_t PointTree::build(uint32_t begin, uint32_t end) {
  Node n;
  n.begin = begin;
  n.end = end;
  n.lo = n.hi = m_points[begin];
  for (uint32_t i = begin; i < end; ++i) {
    n.lo = glm::min(n.lo, m_points[i]);
    n.hi = glm::max(n.hi, m_points[i]);
  }
  const auto index = int32_t(m_nodes.size());
  m_nodes.push_back(n);
  if (end - begin <= kLeafPoints) return index;
  const glm::vec3 size = n.hi - n.lo;
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(m_points.begin() + begin, m_points.begin() + mid, m_points.begin() + end,
                   [axis](const glm::vec3& a, const glm::vec3& b) { return a[axis] < b[axis]; });
  const int32_t left = build(begin, mid);
  const int32_t right = build(mid, end);
  m_nodes[size_t(index)].left = left;
  m_nodes[size_t(index)].right = right;
  return index;
}

template <class Value, class Bound>
float PointTree::search(Value value, Bound bound) const {
  float best = -std::numeric_limits<float>::infinity();
  std::vector<int32_t> stack{0};
  while (!stack.empty()) {
    const Node& n = m_nodes[size_t(stack.back())];
    stack.pop_back();
    if (padded(bound(n)) < double(best)) continue;
    if (n.left < 0) {
      for (uint32_t i = n.begin; i < n.end; ++i)
        best = std::max(best, value(m_points[i]));
      continue;
    }
    // The more promising child last, so it is searched first.
    const double l = bound(m_nodes[size_t(n.left)]), r = bound(m_nodes[size_t(n.right)]);
    stack.push_back(l > r ? n.right : n.left);
    stack.push_back(l > r ? n.left : n.right);
  }
  return best;
}

Bounds PointTree::moved_bounds(const glm::dmat4& t) const {
  Bounds b;
  if (empty()) return b;
  for (int k = 0; k < 3; ++k) {
    for (double sign : {1.0, -1.0}) {
      const float v = search([&](const glm::vec3& p) { return float(sign) * moved(t, p)[k]; },
                             [&](const Node& n) {
                               double m = -std::numeric_limits<double>::infinity();
                               for (const glm::dvec3& c : moved_corners(t, n.lo, n.hi))
                                 m = std::max(m, sign * c[k]);
                               return m;
                             });
      (sign > 0.0 ? b.max : b.min)[k] = float(sign) * v;
    }
  }
  return b;
}

float PointTree::max_distance2(const glm::dmat4& t, const glm::vec3& c) const {
  if (empty()) return 0.0f;
  const glm::dvec3 centre(c);
  return search(
      [&](const glm::vec3& p) {
        const glm::vec3 d = moved(t, p) - c;
        return glm::dot(d, d);
      },
      [&](const Node& n) {
        double m = 0.0;
        for (const glm::dvec3& q : moved_corners(t, n.lo, n.hi))
          m = std::max(m, glm::dot(q - centre, q - centre));
        return m;
      });
}

}  // namespace sylva
