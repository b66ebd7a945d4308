// Marching cubes on analytic fields (sphere, plane, two spheres, single corners, every cube
// configuration, random and saddle fields) and the OpenMesh surface optimisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "core/error.h"
#include "npr/implicit_surface.h"
#include "npr/scalar_grid.h"

namespace sylva {
namespace {

using Field = std::function<float(const glm::vec3&)>;

// Built by hand: make_grid/sample belong to another unit.
ScalarGrid grid_of(const glm::vec3& origin, const glm::ivec3& dims, float spacing, const Field& f) {
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
ScalarGrid cube_grid(const glm::vec3& centre, float half, int cells, const Field& f) {
  const float h = 2.0f * half / float(cells);
  return grid_of(centre - glm::vec3(half), glm::ivec3(cells + 1), h, f);
}

Field sphere(const glm::vec3& c, float r) {
  return [c, r](const glm::vec3& p) { return r - glm::length(p - c); };
}

using Edge = std::pair<uint32_t, uint32_t>;

std::map<Edge, int> undirected_edges(const SurfaceMesh& m) {
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
bool directed_edges_unique(const SurfaceMesh& m) {
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

bool watertight(const SurfaceMesh& m) {
  for (const auto& [edge, count] : undirected_edges(m)) {
    if (count != 2) return false;
  }
  return directed_edges_unique(m);
}

long euler_characteristic(const SurfaceMesh& m) {
  return long(m.positions.size()) - long(undirected_edges(m).size()) + long(m.triangle_count());
}

glm::dvec3 triangle_cross(const SurfaceMesh& m, size_t t) {
  const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
      c(m.positions[m.indices[3 * t + 2]]);
  return glm::cross(b - a, c - a);
}

glm::vec3 centroid(const SurfaceMesh& m, size_t t) {
  return (m.positions[m.indices[3 * t]] + m.positions[m.indices[3 * t + 1]] +
          m.positions[m.indices[3 * t + 2]]) /
         3.0f;
}

double total_area(const SurfaceMesh& m) {
  double a = 0;
  for (size_t t = 0; t < m.triangle_count(); ++t)
    a += 0.5 * glm::length(triangle_cross(m, t));
  return a;
}

// Indices in range, every vertex used, positions finite, no repeated-index or zero-area
// triangle, normals left empty.
void expect_sane(const SurfaceMesh& m) {
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
void expect_outward(const SurfaceMesh& m, const glm::vec3& c) {
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    ASSERT_GT(glm::dot(triangle_cross(m, t), glm::dvec3(centroid(m, t) - c)), 0.0)
        << "triangle " << t;
  }
}

double max_radius_error(const SurfaceMesh& m, const glm::vec3& c, float r) {
  double e = 0;
  for (const glm::vec3& p : m.positions)
    e = std::max(e, std::abs(double(glm::length(p - c)) - r));
  return e;
}

int components(const SurfaceMesh& m) {
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
void expect_closed_inside_grid(const ScalarGrid& g, const SurfaceMesh& m) {
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

bool same_bytes(const SurfaceMesh& a, const SurfaceMesh& b) {
  return a.positions.size() == b.positions.size() && a.indices == b.indices &&
         std::memcmp(a.positions.data(), b.positions.data(),
                     a.positions.size() * sizeof(glm::vec3)) == 0;
}

const glm::vec3 kCentre(0.013f, 0.021f, 0.007f);

TEST(Isosurface, FineSphereIsAccurateWatertightAndOutward) {
  const float h = 0.05f;
  const ScalarGrid g = cube_grid(kCentre, 1.3f, 52, sphere(kCentre, 1.0f));
  ASSERT_NEAR(g.spacing, h, 1e-6);
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_GT(m.triangle_count(), 5000u);
  EXPECT_LT(max_radius_error(m, kCentre, 1.0f), 0.1 * h);
  EXPECT_TRUE(watertight(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  EXPECT_EQ(components(m), 1);
  expect_outward(m, kCentre);
  EXPECT_NEAR(total_area(m), 4.0 * M_PI, 0.01 * 4.0 * M_PI);
}

TEST(Isosurface, CoarseSphereIsWatertightAndOutward) {
  const ScalarGrid g = cube_grid(kCentre, 2.0f, 8, sphere(kCentre, 1.0f));
  ASSERT_FLOAT_EQ(g.spacing, 0.5f);
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_LT(max_radius_error(m, kCentre, 1.0f), 0.25 * 0.5);
  EXPECT_TRUE(watertight(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  expect_outward(m, kCentre);
}

TEST(Isosurface, SphereThroughGridNodesHandlesExactZeros) {
  // Integer nodes at distance exactly 5 ((5,0,0), (3,4,0), (0,3,4), ...) sample F = 0.
  const ScalarGrid g = cube_grid(glm::vec3(0.0f), 7.0f, 14, sphere(glm::vec3(0.0f), 5.0f));
  size_t zeros = size_t(std::count(g.values.begin(), g.values.end(), 0.0f));
  ASSERT_GT(zeros, 20u);
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_LT(max_radius_error(m, glm::vec3(0.0f), 5.0f), 0.1);
  EXPECT_TRUE(watertight(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  expect_outward(m, glm::vec3(0.0f));
  // Zero nodes are outside, so the surface passes through them: each is a vertex.
  size_t on_node = 0;
  for (const glm::vec3& p : m.positions)
    on_node += glm::length(p) == 5.0f;
  EXPECT_EQ(on_node, zeros);
}

TEST(Isosurface, NoSignChangeGivesEmptyMesh) {
  for (float v : {-1.0f, 0.0f, 2.0f}) {
    const ScalarGrid g = cube_grid(glm::vec3(0.0f), 1.0f, 6, [v](const glm::vec3&) { return v; });
    const SurfaceMesh m = extract_isosurface(g);
    EXPECT_TRUE(m.positions.empty()) << v;
    EXPECT_TRUE(m.indices.empty()) << v;
  }
  EXPECT_EQ(extract_isosurface(ScalarGrid{}).triangle_count(), 0u);
}

TEST(Isosurface, SurfaceLeavingTheGridIsOpenOnlyAtTheGridBoundary) {
  // Only the upper part of the sphere (and its inside) is in the box.
  const float h = 0.1f;
  const ScalarGrid g = grid_of(kCentre + glm::vec3(-1.25f, -1.25f, -0.33f), glm::ivec3(26, 26, 17),
                               h, sphere(kCentre, 1.0f));
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_FALSE(watertight(m));
  expect_closed_inside_grid(g, m);
  size_t open = 0;
  for (const auto& [e, count] : undirected_edges(m))
    open += count == 1;
  EXPECT_GT(open, 10u);
  expect_outward(m, kCentre);
  // A box whose every sample is inside: the surface lies outside the box, nothing to mesh.
  const ScalarGrid inner = cube_grid(kCentre, 0.5f, 10, sphere(kCentre, 1.0f));
  EXPECT_EQ(extract_isosurface(inner).triangle_count(), 0u);
}

TEST(Isosurface, TwoSeparateSpheresGiveTwoClosedComponents) {
  const glm::vec3 c1(-0.8f, 0.01f, 0.02f), c2(0.83f, -0.02f, 0.01f);
  const ScalarGrid g = grid_of(
      glm::vec3(-1.6f, -0.8f, -0.8f), glm::ivec3(65, 33, 33), 0.05f, [&](const glm::vec3& p) {
        return std::max(0.6f - glm::length(p - c1), 0.6f - glm::length(p - c2));
      });
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_EQ(components(m), 2);
  EXPECT_TRUE(watertight(m));
  EXPECT_EQ(euler_characteristic(m), 4);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 q = centroid(m, t);
    const glm::vec3 c = glm::length(q - c1) < glm::length(q - c2) ? c1 : c2;
    ASSERT_GT(glm::dot(triangle_cross(m, t), glm::dvec3(q - c)), 0.0);
  }
}

TEST(Isosurface, PlaneIsFlatCoversTheCrossSectionAndFacesUp) {
  const glm::ivec3 dims(11, 9, 7);
  const float h = 0.1f;
  for (float z0 : {0.537f, 0.6f}) {  // between nodes, and (about) on a node plane
    const ScalarGrid g = grid_of(glm::vec3(0.1f, -0.2f, 0.3f), dims, h,
                                 [z0](const glm::vec3& p) { return z0 - p.z; });
    const SurfaceMesh m = extract_isosurface(g);
    expect_sane(m);
    for (const glm::vec3& p : m.positions)
      ASSERT_NEAR(p.z, z0, 1e-5);
    EXPECT_NEAR(total_area(m), double(dims.x - 1) * double(dims.y - 1) * h * h, 1e-4);
    for (size_t t = 0; t < m.triangle_count(); ++t)
      ASSERT_GT(triangle_cross(m, t).z, 0.0);
    expect_closed_inside_grid(g, m);
  }
  // Exactly on a node plane: every vertex is a node of that plane.
  const ScalarGrid g =
      grid_of(glm::vec3(0.0f), dims, 0.25f, [](const glm::vec3& p) { return 0.75f - p.z; });
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_EQ(m.positions.size(), size_t(dims.x) * size_t(dims.y));
  EXPECT_EQ(m.triangle_count(), size_t(2 * (dims.x - 1) * (dims.y - 1)));
  for (const glm::vec3& p : m.positions)
    ASSERT_EQ(p.z, 0.75f);
  EXPECT_NEAR(total_area(m), double(dims.x - 1) * double(dims.y - 1) * 0.0625, 1e-9);
}

ScalarGrid unit_cell(int config, const std::array<float, 8>& magnitude) {
  ScalarGrid g;
  g.dims = glm::ivec3(2);
  g.values.resize(8);
  for (int c = 0; c < 8; ++c) {
    const float m = magnitude[size_t(c)];
    g.values[g.index(c & 1, (c >> 1) & 1, (c >> 2) & 1)] = ((config >> c) & 1) ? m : -m;
  }
  return g;
}

TEST(Isosurface, OneCornerGivesOneTriangleFacingAwayFromTheInside) {
  std::array<float, 8> ones;
  ones.fill(1.0f);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
    for (bool inverted : {false, true}) {
      const int config = inverted ? 255 ^ (1 << c) : 1 << c;
      const SurfaceMesh m = extract_isosurface(unit_cell(config, ones));
      expect_sane(m);
      ASSERT_EQ(m.triangle_count(), 1u) << c;
      for (const glm::vec3& p : m.positions)
        EXPECT_NEAR(glm::length(p - corner), 0.5f, 1e-6);
      // Outside (F < 0) is away from a lone inside corner, towards a lone outside one.
      const double side = glm::dot(triangle_cross(m, 0), glm::dvec3(centroid(m, 0) - corner));
      EXPECT_EQ(side > 0, !inverted) << c;
    }
  }
}

TEST(Isosurface, EveryCellConfigurationIsConsistent) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mag(0.05f, 1.0f);
  int centres = 0;
  for (int config = 1; config < 255; ++config) {
    for (int trial = 0; trial < 8; ++trial) {
      std::array<float, 8> m;
      for (float& v : m)
        v = mag(rng);
      const ScalarGrid g = unit_cell(config, m);
      const SurfaceMesh s = extract_isosurface(g);
      expect_sane(s);
      ASSERT_GT(s.triangle_count(), 0u) << config;
      ASSERT_LE(s.triangle_count(), 12u) << config;
      expect_closed_inside_grid(g, s);
      // Each vertex lies on a cell edge (two coordinates are 0 or 1), except the centre
      // vertex of a loop that crosses a face twice, strictly inside the cell.
      for (const glm::vec3& p : s.positions) {
        int on = 0, in = 0;
        for (int k = 0; k < 3; ++k) {
          on += p[k] == 0.0f || p[k] == 1.0f;
          in += p[k] > 0.0f && p[k] < 1.0f;
        }
        ASSERT_TRUE(on >= 2 || in == 3) << config;
        centres += in == 3;
      }
    }
  }
  EXPECT_LT(centres, 8 * 254 / 20);  // rare
}

TEST(Isosurface, RandomAndSaddleFieldsAreCleanManifolds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::ivec3 dims(13, 12, 11);
  // Random values; a checkerboard where every face is ambiguous; a thin shell.
  const std::vector<Field> fields = {
      [&](const glm::vec3&) { return u(rng); },
      [&](const glm::vec3& p) {
        const int s = (int(std::lround(p.x)) + int(std::lround(p.y)) + int(std::lround(p.z))) & 1;
        return (s ? 1.0f : -1.0f) * (0.5f + 0.5f * std::abs(u(rng)));
      },
      [](const glm::vec3& p) { return 0.3f - std::abs(glm::length(p - glm::vec3(6.1f)) - 4.0f); },
      [](const glm::vec3& p) {
        return std::sin(1.7f * p.x) * std::sin(1.9f * p.y) * std::sin(2.3f * p.z);
      },
  };
  for (size_t i = 0; i < fields.size(); ++i) {
    const ScalarGrid g = grid_of(glm::vec3(0.0f), dims, 1.0f, fields[i]);
    const SurfaceMesh m = extract_isosurface(g);
    SCOPED_TRACE(i);
    expect_sane(m);
    EXPECT_GT(m.triangle_count(), 100u);
    expect_closed_inside_grid(g, m);
  }
}

TEST(Isosurface, ManyExactZerosGiveNoDegenerateTriangles) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(-1, 1);
  const ScalarGrid g = grid_of(glm::vec3(-1.0f), glm::ivec3(12, 11, 10), 0.2f,
                               [&](const glm::vec3&) { return float(pick(rng)); });
  const SurfaceMesh m = extract_isosurface(g);
  expect_sane(m);
  EXPECT_GT(m.triangle_count(), 10u);
  // Inside-only neighbours of a zero node put the surface through that node.
  ScalarGrid point;
  point.dims = glm::ivec3(3);
  point.values.assign(27, 0.0f);
  point.values[point.index(1, 1, 1)] = 1.0f;
  const SurfaceMesh octahedron = extract_isosurface(point);
  expect_sane(octahedron);
  EXPECT_EQ(octahedron.positions.size(), 6u);
  EXPECT_EQ(octahedron.triangle_count(), 8u);
  EXPECT_TRUE(watertight(octahedron));
  expect_outward(octahedron, glm::vec3(1.0f));
}

TEST(Isosurface, NonFiniteSamplesGiveFiniteVertices) {
  ScalarGrid g = cube_grid(kCentre, 1.3f, 13, sphere(kCentre, 1.0f));
  g.values[g.index(3, 6, 6)] = std::numeric_limits<float>::quiet_NaN();
  g.values[g.index(6, 6, 6)] = std::numeric_limits<float>::infinity();
  g.values[g.index(0, 0, 0)] = -std::numeric_limits<float>::infinity();
  expect_sane(extract_isosurface(g));
}

TEST(Isosurface, OutputIsDeterministic) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.02f, 0.02f);
  const ScalarGrid g = cube_grid(kCentre, 1.3f, 40, [&](const glm::vec3& p) {
    return 1.0f - glm::length(p - kCentre) + u(rng);
  });
  EXPECT_TRUE(same_bytes(extract_isosurface(g), extract_isosurface(g)));
}

double radius_variance(const SurfaceMesh& m, const glm::vec3& c) {
  double s = 0, s2 = 0;
  for (const glm::vec3& p : m.positions) {
    const double r = glm::length(p - c);
    s += r;
    s2 += r * r;
  }
  const double n = double(m.positions.size());
  return s2 / n - (s / n) * (s / n);
}

SurfaceMesh noisy_sphere(float noise, int cells = 52) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-noise, noise);
  return extract_isosurface(cube_grid(kCentre, 1.3f, cells, [&](const glm::vec3& p) {
    return 1.0f - glm::length(p - kCentre) + u(rng);
  }));
}

TEST(SurfaceOptimize, SmoothingReducesRoughness) {
  SurfaceMesh m = noisy_sphere(0.02f);
  ASSERT_TRUE(watertight(m));
  const double before = radius_variance(m, kCentre);
  const size_t faces = m.triangle_count();
  optimize_surface(m, {10, 1.0});
  expect_sane(m);
  EXPECT_EQ(m.triangle_count(), faces);
  EXPECT_TRUE(watertight(m));
  const double after = radius_variance(m, kCentre);
  EXPECT_LT(after, 0.25 * before) << before << " -> " << after;
  EXPECT_LT(max_radius_error(m, kCentre, 1.0f), 0.05);  // some shrinkage, no collapse
  expect_outward(m, kCentre);
}

TEST(SurfaceOptimize, DecimationKeepsTheShareAndTheShape) {
  SurfaceMesh m = extract_isosurface(cube_grid(kCentre, 1.3f, 52, sphere(kCentre, 1.0f)));
  const size_t faces = m.triangle_count();
  optimize_surface(m, {0, 0.25});
  expect_sane(m);
  EXPECT_NEAR(double(m.triangle_count()), 0.25 * double(faces), 0.025 * double(faces));
  EXPECT_TRUE(watertight(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  EXPECT_LT(max_radius_error(m, kCentre, 1.0f), 0.01);
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    ASSERT_GT(glm::length(centroid(m, t) - kCentre), 0.95f);
  }
  expect_outward(m, kCentre);
}

TEST(SurfaceOptimize, SmoothAndDecimateTogetherAndOnOpenSurfaces) {
  SurfaceMesh closed = noisy_sphere(0.01f, 26);
  optimize_surface(closed, {5, 0.5});
  expect_sane(closed);
  EXPECT_TRUE(watertight(closed));
  expect_outward(closed, kCentre);

  const ScalarGrid g = grid_of(kCentre + glm::vec3(-1.25f, -1.25f, -0.33f), glm::ivec3(26, 26, 17),
                               0.1f, sphere(kCentre, 1.0f));
  SurfaceMesh open = extract_isosurface(g);
  optimize_surface(open, {100, 0.1});
  expect_sane(open);
  EXPECT_GT(open.triangle_count(), 0u);
  EXPECT_TRUE(directed_edges_unique(open));
}

TEST(SurfaceOptimize, ExtremeValuesAreAccepted) {
  SurfaceMesh m = extract_isosurface(cube_grid(kCentre, 2.0f, 8, sphere(kCentre, 1.0f)));
  optimize_surface(m, {100, 1e-6});
  expect_sane(m);
  EXPECT_GT(m.triangle_count(), 0u);
  SurfaceMesh empty;
  optimize_surface(empty, {3, 0.5});
  EXPECT_EQ(empty.triangle_count(), 0u);
}

TEST(SurfaceOptimize, InvalidOptionsThrowInputError) {
  const SurfaceMesh base = extract_isosurface(cube_grid(kCentre, 2.0f, 8, sphere(kCentre, 1.0f)));
  auto where = [&](SurfaceOptimizeOptions o) -> std::string {
    SurfaceMesh m = base;
    try {
      optimize_surface(m, o);
    } catch (const InputError& e) {
      EXPECT_TRUE(same_bytes(m, base)) << "mesh changed before the error";
      return e.where();
    }
    return "";
  };
  EXPECT_EQ(where({-1, 1.0}), "smooth");
  EXPECT_EQ(where({101, 1.0}), "smooth");
  EXPECT_EQ(where({0, 0.0}), "decimate");
  EXPECT_EQ(where({0, -0.5}), "decimate");
  EXPECT_EQ(where({0, 1.5}), "decimate");
  EXPECT_EQ(where({0, std::nan("")}), "decimate");
  EXPECT_EQ(where({0, std::numeric_limits<double>::infinity()}), "decimate");
}

TEST(SurfaceOptimize, NoSmoothingAndFullKeepLeaveTheMeshIdentical) {
  const SurfaceMesh base = noisy_sphere(0.02f);
  SurfaceMesh m = base;
  optimize_surface(m, {0, 1.0});
  EXPECT_TRUE(same_bytes(m, base));
}

TEST(SurfaceOptimize, OutputIsDeterministic) {
  const SurfaceMesh base = noisy_sphere(0.02f, 26);
  SurfaceMesh a = base, b = base;
  optimize_surface(a, {3, 0.3});
  optimize_surface(b, {3, 0.3});
  EXPECT_TRUE(same_bytes(a, b));
}

}  // namespace
}  // namespace sylva
