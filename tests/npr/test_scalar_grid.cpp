// Scalar grid: make_grid dims/spacing/origin, trilinear sampling and its gradient exact for
// linear functions, clamping outside the box, the cell-count range.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "npr/scalar_grid.h"

namespace sylva {
namespace {

// Grid holding f(p) = a . p + b at its nodes.
ScalarGrid linear_grid(const glm::vec3& a, float b) {
  ScalarGrid g = make_grid({-1.0f, 0.0f, 2.0f}, {3.0f, 1.0f, 4.0f}, 16);
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x)
        g.values[g.index(x, y, z)] = glm::dot(a, g.position(x, y, z)) + b;
  return g;
}

TEST(Grid, MakeGridDimsForABox) {
  const glm::vec3 lo(-1.0f, 0.0f, 2.0f), hi(3.0f, 1.0f, 4.0f);  // extents 4, 1, 2
  ScalarGrid g = make_grid(lo, hi, 16);
  EXPECT_FLOAT_EQ(g.spacing, 0.25f);
  EXPECT_EQ(g.dims, glm::ivec3(17, 5, 9));
  EXPECT_EQ(g.values.size(), size_t(17 * 5 * 9));
  for (float v : g.values)
    EXPECT_EQ(v, 0.0f);
  EXPECT_FLOAT_EQ(g.origin.x, -1.0f);
  // Every axis covers the box.
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(g.origin[a], lo[a] + 1e-6f);
    EXPECT_GE(g.origin[a] + g.spacing * float(g.dims[a] - 1), hi[a] - 1e-6f);
  }
  EXPECT_EQ(g.index(1, 2, 3), size_t(1 + 17 * (2 + 5 * 3)));
}

TEST(Grid, MakeGridThinAxesGetAtLeastTwoCellsAndAreCentred) {
  ScalarGrid g = make_grid({0.0f, 5.0f, 0.0f}, {10.0f, 5.0f, 0.1f}, 100);  // flat in y
  EXPECT_EQ(g.dims.x, 101);
  EXPECT_EQ(g.dims.y, 3);
  EXPECT_EQ(g.dims.z, 3);
  EXPECT_NEAR(g.origin.y + g.spacing, 5.0f, 1e-5f);  // the box is the middle node
  EXPECT_NEAR(g.origin.z + g.spacing, 0.05f, 1e-5f);

  ScalarGrid point = make_grid(glm::vec3(2.0f), glm::vec3(2.0f), 2);
  EXPECT_EQ(point.dims, glm::ivec3(3));
  EXPECT_GT(point.spacing, 0.0f);
  EXPECT_FLOAT_EQ(point.position(1, 1, 1).x, 2.0f);
}

TEST(Grid, CellRange) {
  EXPECT_THROW(make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 1), InputError);
  EXPECT_THROW(make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 1025), InputError);
  EXPECT_THROW(make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 0), InputError);
  EXPECT_THROW(make_grid(glm::vec3(1.0f), glm::vec3(0.0f), 8), InputError);
  EXPECT_THROW(make_grid(glm::vec3(0.0f), glm::vec3(NAN), 8), InputError);
  try {
    make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 1025);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "grid");
  }
  EXPECT_EQ(make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 2).dims, glm::ivec3(3));
  EXPECT_EQ(make_grid(glm::vec3(0.0f), glm::vec3(1.0f, 0.01f, 0.0f), 1024).dims,
            glm::ivec3(1025, 12, 3));
}

TEST(Grid, SampleExactForLinearFunction) {
  const glm::vec3 a(0.7f, -1.3f, 2.1f);
  const float b = 0.4f;
  ScalarGrid g = linear_grid(a, b);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> ux(-1.0f, 3.0f), uy(0.0f, 1.0f), uz(2.0f, 4.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p(ux(rng), uy(rng), uz(rng));
    EXPECT_NEAR(g.sample(p), glm::dot(a, p) + b, 1e-5f);
  }
  // Nodes, including the last one on each axis.
  for (glm::ivec3 n : {glm::ivec3(0), g.dims - 1, glm::ivec3(3, 4, 8)})
    EXPECT_NEAR(g.sample(g.position(n.x, n.y, n.z)), g.at(n.x, n.y, n.z), 1e-5f);
}

TEST(Grid, GradientExactForLinearFunction) {
  const glm::vec3 a(0.7f, -1.3f, 2.1f);
  ScalarGrid g = linear_grid(a, -3.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> ux(-1.0f, 3.0f), uy(0.0f, 1.0f), uz(2.0f, 4.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 gr = g.sample_gradient({ux(rng), uy(rng), uz(rng)});
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(gr[k], a[k], 1e-4f);
  }
  // At nodes and on the far faces too.
  for (glm::ivec3 n : {glm::ivec3(0), g.dims - 1})
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(g.sample_gradient(g.position(n.x, n.y, n.z))[k], a[k], 1e-4f);
}

TEST(Grid, GradientOfTrilinearMatchesFiniteDifferences) {
  ScalarGrid g = make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 4);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> val(-1.0f, 1.0f);
  for (float& v : g.values)
    v = val(rng);
  std::uniform_real_distribution<float> pos(0.01f, 0.99f);
  const float h = 1e-3f;
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 p(pos(rng), pos(rng), pos(rng));
    const glm::vec3 gr = g.sample_gradient(p);
    for (int k = 0; k < 3; ++k) {
      glm::vec3 e(0.0f);
      e[k] = h;
      // Skip points whose stencil crosses a cell face (the interpolant's kink).
      const glm::vec3 ua = (p - e) / g.spacing, ub = (p + e) / g.spacing;
      if (std::floor(ua[k]) != std::floor(ub[k])) continue;
      const float fd = (g.sample(p + e) - g.sample(p - e)) / (2.0f * h);
      EXPECT_NEAR(gr[k], fd, 2e-2f);
    }
  }
}

TEST(Grid, ClampsOutsideTheBox) {
  const glm::vec3 a(1.0f, 2.0f, 3.0f);
  ScalarGrid g = linear_grid(a, 0.0f);
  const glm::vec3 lo = g.origin, hi = g.position(g.dims.x - 1, g.dims.y - 1, g.dims.z - 1);
  const glm::vec3 outside(lo.x - 5.0f, hi.y + 2.0f, 3.0f);
  const glm::vec3 clamped(lo.x, hi.y, 3.0f);
  EXPECT_NEAR(g.sample(outside), glm::dot(a, clamped), 1e-5f);
  EXPECT_EQ(g.sample_gradient(outside), g.sample_gradient(clamped));
  EXPECT_NEAR(g.sample(glm::vec3(1e30f)), glm::dot(a, hi), 1e-4f);
  EXPECT_NEAR(g.sample(glm::vec3(-INFINITY)), glm::dot(a, lo), 1e-4f);
  // NaN does not index out of range or produce NaN.
  EXPECT_TRUE(std::isfinite(g.sample(glm::vec3(NAN))));
  EXPECT_TRUE(std::isfinite(g.sample_gradient(glm::vec3(NAN)).x));
}

}  // namespace
}  // namespace sylva
