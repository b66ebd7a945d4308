// Checks of triangle meshes made by marching cubes (tests/npr/test_implicit_surface.cpp,
// test_surface_optimize.cpp): analytic fields on hand-built grids, edge topology, orientation,
// areas and byte equality.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "npr/implicit_surface.h"
#include "npr/scalar_grid.h"

namespace sylva::mesh_checks {

using Field = std::function<float(const glm::vec3&)>;

// Built by hand: make_grid/sample belong to another unit.
inline ScalarGrid grid_of(const glm::vec3& origin, const glm::ivec3& dims, float spacing,
                          const Field& f) {
  ScalarGrid g;
  g.dims = dims;
  g.origin = origin;
  g.spacing = spacing;
  g.values.resize(size_t(dims.x) * size_t(dims.y) * size_t(dims.z));
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x)
        g.values[g.index(x, y, z)] = f(g.position(x, y, z));
    }
  }
  return g;
}

// A cube of side 2 * half around `centre`, `cells` cells per axis.
inline ScalarGrid cube_grid(const glm::vec3& centre, float half, int cells, const Field& f) {
  const float h = 2.0f * half / float(cells);
  return grid_of(centre - glm::vec3(half), glm::ivec3(cells + 1), h, f);
}

inline Field sphere(const glm::vec3& c, float r) {
  return [c, r](const glm::vec3& p) { return r - glm::length(p - c); };
}

using Edge = std::pair<uint32_t, uint32_t>;

inline std::map<Edge, int> undirected_edges(const SurfaceMesh& m) {
  std::map<Edge, int> e;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = m.indices[3 * t + size_t(k)], b = m.indices[3 * t + size_t((k + 1) % 3)];
      ++e[{std::min(a, b), std::max(a, b)}];
    }
  }
  return e;
}

// Every directed edge at most once: neighbouring triangles are consistently oriented.
inline bool directed_edges_unique(const SurfaceMesh& m) {
  std::map<Edge, int> e;
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (++e[{m.indices[3 * t + size_t(k)], m.indices[3 * t + size_t((k + 1) % 3)]}] > 1) {
        return false;
      }
    }
  }
  return true;
}

inline bool watertight(const SurfaceMesh& m) {
  for (const auto& [edge, count] : undirected_edges(m)) {
    if (count != 2) return false;
  }
  return directed_edges_unique(m);
}

inline long euler_characteristic(const SurfaceMesh& m) {
  return long(m.positions.size()) - long(undirected_edges(m).size()) + long(m.triangle_count());
}

inline glm::dvec3 triangle_cross(const SurfaceMesh& m, size_t t) {
  const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
      c(m.positions[m.indices[3 * t + 2]]);
  return glm::cross(b - a, c - a);
}

inline glm::vec3 centroid(const SurfaceMesh& m, size_t t) {
  return (m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] +
          m.positions[m.indices[3 * t + 2]]) /
         3.0f;
}

inline double total_area(const SurfaceMesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    a += 0.5 * glm::length(triangle_cross(m, t));
  return a;
}

// Indices in range, every vertex used, positions finite, no repeated-index or zero-area
// triangle, normals left empty.
inline void expect_sane(const SurfaceMesh& m) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  EXPECT_TRUE(m.normals.empty());
  std::vector<bool> used(m.positions.size(), false);
  for (uint32_t i : m.indices) {
    ASSERT_LT(i, m.positions.size());
    used[i] = true;
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  for (const glm::vec3& p : m.positions) {
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  }
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    ASSERT_TRUE(a != b && b != c && c != a) << "triangle " << t;
    const glm::dvec3 n = triangle_cross(m, t);
    ASSERT_GT(glm::dot(n, n), 0.0) << "zero-area triangle " << t;
  }
}

// Every triangle faces away from `c` (counter-clockwise seen from outside).
inline void expect_outward(const SurfaceMesh& m, const glm::vec3& c) {
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    ASSERT_GT(glm::dot(triangle_cross(m, t), glm::dvec3(centroid(m, t) - c)), 0.0)
        << "triangle " << t;
  }
}

inline double max_radius_error(const SurfaceMesh& m, const glm::vec3& c, float r) {
  double e = 0;
  for (const glm::vec3& p : m.positions)
    e = std::max(e, std::abs(double(glm::length(p - c)) - r));
  return e;
}

inline int components(const SurfaceMesh& m) {
  std::vector<uint32_t> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::function<uint32_t(uint32_t)> find = [&](uint32_t i) {
    return parent[i] == i ? i : parent[i] = find(parent[i]);
  };
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    parent[find(m.indices[3 * t + 1])] = find(m.indices[3 * t]);
    parent[find(m.indices[3 * t + 2])] = find(m.indices[3 * t]);
  }
  int n = 0;
  for (uint32_t i = 0; i < parent.size(); ++i)
    n += find(i) == i;
  return n;
}

// Interior edges are shared by exactly two consistently oriented triangles; edges used
// once lie on the grid's boundary faces.
inline void expect_closed_inside_grid(const ScalarGrid& g, const SurfaceMesh& m) {
  EXPECT_TRUE(directed_edges_unique(m));
  for (const auto& [e, count] : undirected_edges(m)) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      const glm::vec3 a = m.positions[e.first], b = m.positions[e.second];
      bool shared_plane = false;
      const glm::vec3 lo = g.origin, hi = g.position(g.dims.x - 1, g.dims.y - 1, g.dims.z - 1);
      for (int k = 0; k < 3; ++k) {
        shared_plane |= (a[k] == lo[k] && b[k] == lo[k]) || (a[k] == hi[k] && b[k] == hi[k]);
      }
      ASSERT_TRUE(shared_plane) << "open edge inside the grid";
    }
  }
}

inline bool same_bytes(const SurfaceMesh& a, const SurfaceMesh& b) {
  return a.positions.size() == b.positions.size() && a.indices == b.indices &&
         std::memcmp(a.positions.data(), b.positions.data(),
                     a.positions.size() * sizeof(glm::vec3)) == 0;
}

inline const glm::vec3 kCentre(0.013f, 0.021f, 0.007f);

}  // namespace sylva::mesh_checks
