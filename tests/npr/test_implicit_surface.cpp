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

#include "tests/npr/mesh_checks.h"

namespace sylva {
namespace {

using namespace mesh_checks;

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

}  // namespace
}  // namespace sylva
