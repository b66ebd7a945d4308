// The extent of one point set under many transforms (a plant's vertices under its instances,
// for Scene::bounds and Scene::framing_sphere): a kd-tree of boxes searched by branch and
// bound, so each instance costs a few hundred points instead of all of them. Exact: the
// results equal those of moving every point (in double, rounded to float, as the glTF reader
// flattens nodes) and taking the extremes, because a subtree is skipped only when its box,
// moved by the transform, cannot beat the best value found (with a margin for the rounding).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

class PointTree {
 public:
  explicit PointTree(std::vector<glm::vec3> points);
  bool empty() const { return m_points.empty(); }

  // The bounds of vec3(t * dvec4(p, 1)) over the points.
  Bounds moved_bounds(const glm::dmat4& t) const;
  // The largest dot(d, d), d = vec3(t * dvec4(p, 1)) - c (float), over the points.
  float max_distance2(const glm::dmat4& t, const glm::vec3& c) const;

 private:
  struct Node {
    glm::vec3 lo, hi;  // the box of its points
    uint32_t begin = 0, end = 0;
    int32_t left = -1, right = -1;  // children; -1: a leaf
  };
  int32_t build(uint32_t begin, uint32_t end);
  // Branch and bound: the largest value(p) over the points, `bound(node)` never below the
  // value of any point in the node.
  template <class Value, class Bound>
  float search(Value value, Bound bound) const;

  std::vector<glm::vec3> m_points;
  std::vector<Node> m_nodes;
};

}  // namespace sylva
