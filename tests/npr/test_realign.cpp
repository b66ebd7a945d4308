#include "npr/realign.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace sylva {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (;;) {
    const glm::vec3 v(g(rng), g(rng), g(rng));
    const float len = glm::length(v);
    if (len > 1e-3f) return v / len;
  }
}

// The reference: squared distances in double, ties to the lower index.
size_t brute_force_nearest(const std::vector<glm::vec3>& positions, const glm::vec3& p) {
  size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < positions.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(positions[i]) - glm::dvec3(p);
    const double d2 = glm::dot(d, d);
    if (d2 < best_d) {
      best_d = d2;
      best = i;
    }
  }
  return best;
}

SurfaceMesh random_surface(std::mt19937& rng, size_t count, float extent) {
  std::uniform_real_distribution<float> u(-extent, extent);
  SurfaceMesh s;
  for (size_t i = 0; i < count; ++i) {
    s.positions.emplace_back(u(rng), u(rng), u(rng));
    s.normals.push_back(random_unit(rng));
  }
  return s;
}

TEST(RealignNearest, MatchesBruteForceOnRandomClouds) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 3; ++trial) {
    const SurfaceMesh surface = random_surface(rng, 1000, 2.0f);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    std::vector<glm::vec3> points;
    for (int i = 0; i < 500; ++i)
      points.emplace_back(u(rng), u(rng), u(rng));
    const std::vector<glm::vec3> got = nearest_surface_normals(surface, points);
    ASSERT_EQ(got.size(), points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const size_t want = brute_force_nearest(surface.positions, points[i]);
      ASSERT_EQ(got[i], surface.normals[want]) << "trial " << trial << " point " << i;
    }
  }
}

TEST(RealignNearest, ExactTiesGoToTheLowerIndex) {
  // Vertices on an integer lattice, each present twice (the duplicate later, with another
  // normal), queried at lattice points (distance-0 ties between duplicates) and cell centres
  // (8 vertices, 16 entries at exactly the same distance).
  std::mt19937 rng(7);
  SurfaceMesh surface;
  std::vector<glm::vec3> lattice;
  for (int x = 0; x < 6; ++x) {
    for (int y = 0; y < 6; ++y) {
      for (int z = 0; z < 6; ++z)
        lattice.emplace_back(x, y, z);
    }
  }
  // Shuffled, so the lower index is not simply the first in any spatial order.
  std::shuffle(lattice.begin(), lattice.end(), rng);
  for (int copy = 0; copy < 2; ++copy) {
    for (const glm::vec3& p : lattice) {
      surface.positions.push_back(p);
      surface.normals.push_back(random_unit(rng));
    }
  }
  std::vector<glm::vec3> points;
  for (int x = 0; x < 5; ++x) {
    for (int y = 0; y < 5; ++y) {
      for (int z = 0; z < 5; ++z) {
        points.emplace_back(x, y, z);
        points.emplace_back(x + 0.5f, y + 0.5f, z + 0.5f);
        points.emplace_back(x + 0.5f, y, z);
      }
    }
  }
  const std::vector<glm::vec3> got = nearest_surface_normals(surface, points);
  for (size_t i = 0; i < points.size(); ++i) {
    const size_t want = brute_force_nearest(surface.positions, points[i]);
    ASSERT_LT(want, lattice.size());  // the reference picks a first copy
    ASSERT_EQ(got[i], surface.normals[want]) << "point " << i;
  }
}

TEST(RealignNearest, SphereInteriorGetsRadialNormals) {
  // Fibonacci sphere of radius 2 centred at c, normals radial (outward).
  const glm::vec3 c(1.0f, -2.0f, 0.5f);
  const int count = 2000;
  SurfaceMesh sphere;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count;
    const double r = std::sqrt(1.0 - y * y);
    const double phi = golden * i;
    const glm::vec3 n(static_cast<float>(r * std::cos(phi)), static_cast<float>(y),
                      static_cast<float>(r * std::sin(phi)));
    sphere.positions.push_back(c + 2.0f * n);
    sphere.normals.push_back(glm::normalize(n));
  }
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> radius(0.6f, 1.95f);
  std::vector<glm::vec3> points;
  std::vector<glm::vec3> radial;
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 dir = random_unit(rng);
    points.push_back(c + radius(rng) * dir);
    radial.push_back(dir);
  }
  const std::vector<glm::vec3> got = nearest_surface_normals(sphere, points);
  for (size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(got[i], sphere.normals[brute_force_nearest(sphere.positions, points[i])]) << i;
    // Sample spacing is about 0.08 rad, so the nearest sample's normal is within that angle.
    EXPECT_GT(glm::dot(got[i], radial[i]), std::cos(0.1f)) << i;
  }
}

TEST(RealignNearest, Deterministic) {
  std::mt19937 rng(5);
  const SurfaceMesh surface = random_surface(rng, 3000, 1.0f);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  std::vector<glm::vec3> points;
  for (int i = 0; i < 20000; ++i)
    points.emplace_back(u(rng), u(rng), u(rng));
  const std::vector<glm::vec3> a = nearest_surface_normals(surface, points);
  const std::vector<glm::vec3> b = nearest_surface_normals(surface, points);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)), 0);
}

TEST(RealignNearest, SingleVertexSurface) {
  SurfaceMesh surface;
  surface.positions = {{3.0f, 4.0f, 5.0f}};
  surface.normals = {glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))};
  const std::vector<glm::vec3> points = {{0, 0, 0}, {3, 4, 5}, {-1e6f, 2e6f, 0}, {1, 1, 1}};
  for (const glm::vec3& n : nearest_surface_normals(surface, points)) {
    EXPECT_EQ(n, surface.normals[0]);
  }
}

TEST(RealignNearest, NoPoints) {
  std::mt19937 rng(3);
  EXPECT_TRUE(nearest_surface_normals(random_surface(rng, 10, 1.0f), {}).empty());
}

TEST(RealignNearest, FarAndNonFinitePointsStayFinite) {
  std::mt19937 rng(11);
  const SurfaceMesh surface = random_surface(rng, 200, 1.0f);
  const std::vector<glm::vec3> points = {{1e6f, 0, 0},      {-1e6f, 1e6f, 1e6f}, {0, 0, 1e30f},
                                         {3e38f, 3e38f, 0}, {kInf, 0, 0},        {0, -kInf, 0},
                                         {kNaN, 0, 0},      {kNaN, kNaN, kNaN}};
  const std::vector<glm::vec3> got = nearest_surface_normals(surface, points);
  ASSERT_EQ(got.size(), points.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_TRUE(finite(got[i])) << i;
    EXPECT_NEAR(glm::length(got[i]), 1.0f, 1e-6f) << i;
  }
  // Far but finite: still the true nearest vertex.
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(got[i], surface.normals[brute_force_nearest(surface.positions, points[i])]) << i;
  }
  // Infinitely far is a tie with every vertex, and NaN is unordered: vertex 0 either way.
  for (size_t i = 4; i < got.size(); ++i)
    EXPECT_EQ(got[i], surface.normals[0]) << i;
}

TEST(RealignNearestDeathTest, BadSurfaceIsAProgrammingError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::vector<glm::vec3> points = {{0, 0, 0}};
  EXPECT_DEATH_IF_SUPPORTED((void)nearest_surface_normals(SurfaceMesh{}, points), "no vertices");
  SurfaceMesh mismatch;
  mismatch.positions = {{0, 0, 0}, {1, 0, 0}};
  mismatch.normals = {{0, 0, 1}};
  EXPECT_DEATH_IF_SUPPORTED((void)nearest_surface_normals(mismatch, points), "one normal");
}

void expect_unit_near(const glm::vec3& got, const glm::vec3& want, float tol = 1e-6f) {
  EXPECT_TRUE(finite(got));
  EXPECT_NEAR(glm::length(got), 1.0f, 1e-6f);
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TEST(RealignBlend, EndsAndBisector) {
  const glm::vec3 n(1.0f, 0.0f, 0.0f);
  const glm::vec3 ns(0.0f, 1.0f, 0.0f);
  expect_unit_near(blend_normal(n, ns, 0.0f), n);
  expect_unit_near(blend_normal(n, ns, 1.0f), ns);
  expect_unit_near(blend_normal(n, ns, 0.5f), glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  // Luft et al. §3.3 linear combination, then normalised: blend 0.25 weighs n three times.
  expect_unit_near(blend_normal(n, ns, 0.25f), glm::normalize(glm::vec3(3.0f, 1.0f, 0.0f)));
}

TEST(RealignBlend, OppositeNormalsAtHalfGiveNs) {
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 2.0f, -3.0f));
  expect_unit_near(blend_normal(n, -n, 0.5f), -n);
  // Nearly opposite: the sum is rounding noise, still ns.
  const glm::vec3 almost = glm::normalize(-n + glm::vec3(1e-8f, 0.0f, 0.0f));
  expect_unit_near(blend_normal(n, almost, 0.5f), almost);
  // Opposite but away from the cancelling blend: a clear direction wins.
  expect_unit_near(blend_normal(n, -n, 0.75f), -n);
  expect_unit_near(blend_normal(n, -n, 0.25f), n);
}

TEST(RealignBlend, ZeroOrUnusableInputs) {
  const glm::vec3 ns = glm::normalize(glm::vec3(0.0f, 3.0f, 4.0f));
  const glm::vec3 n(1.0f, 0.0f, 0.0f);
  expect_unit_near(blend_normal(glm::vec3(0.0f), ns, 0.0f), ns);
  expect_unit_near(blend_normal(glm::vec3(0.0f), ns, 0.5f), ns);
  expect_unit_near(blend_normal(n, glm::vec3(0.0f), 1.0f), n);  // ns unusable: n
  const glm::vec3 both_zero = blend_normal(glm::vec3(0.0f), glm::vec3(0.0f), 0.5f);
  EXPECT_TRUE(finite(both_zero));
  EXPECT_NEAR(glm::length(both_zero), 1.0f, 1e-6f);
}

TEST(RealignBlend, NonUnitInputsGiveUnitOutput) {
  const glm::vec3 n(10.0f, 0.0f, 0.0f);
  const glm::vec3 ns(0.0f, 0.1f, 0.0f);
  // The linear combination uses the vectors as given (normalised afterwards).
  expect_unit_near(blend_normal(n, ns, 0.5f), glm::normalize(glm::vec3(5.0f, 0.05f, 0.0f)));
  expect_unit_near(blend_normal(glm::vec3(1e-30f, 0, 0), glm::vec3(0, 1e-30f, 0), 0.5f),
                   glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  expect_unit_near(blend_normal(glm::vec3(3e38f, 0, 0), glm::vec3(0, 3e38f, 0), 0.5f),
                   glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  expect_unit_near(blend_normal(glm::vec3(3e38f, 3e38f, 3e38f), glm::vec3(0, 0, 1), 0.0f),
                   glm::normalize(glm::vec3(1.0f)));
}

TEST(RealignBlend, NonFiniteInputsGiveFiniteUnitOutput) {
  const glm::vec3 n(1.0f, 0.0f, 0.0f);
  const glm::vec3 ns(0.0f, 0.0f, 1.0f);
  const glm::vec3 nan3(kNaN);
  expect_unit_near(blend_normal(nan3, ns, 0.5f), ns);
  expect_unit_near(blend_normal(n, nan3, 0.5f), n);
  expect_unit_near(blend_normal(glm::vec3(kInf, 0, 0), ns, 0.5f), ns);
  expect_unit_near(blend_normal(n, ns, kNaN), ns);
  const std::vector<glm::vec3> odd = {
      nan3, glm::vec3(kInf), glm::vec3(-kInf, 0, 0), glm::vec3(0.0f), n, ns};
  for (const glm::vec3& a : odd) {
    for (const glm::vec3& b : odd) {
      for (float t : {0.0f, 0.5f, 1.0f, kNaN, kInf}) {
        const glm::vec3 r = blend_normal(a, b, t);
        ASSERT_TRUE(finite(r));
        ASSERT_NEAR(glm::length(r), 1.0f, 1e-6f);
      }
    }
  }
}

TEST(RealignBlend, SweepStaysUnitAndMovesTowardNs) {
  std::mt19937 rng(21);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 n = random_unit(rng);
    const glm::vec3 ns = random_unit(rng);
    float prev = -2.0f;
    for (int k = 0; k <= 20; ++k) {
      const glm::vec3 r = blend_normal(n, ns, static_cast<float>(k) / 20.0f);
      ASSERT_NEAR(glm::length(r), 1.0f, 1e-6f);
      const float toward = glm::dot(r, ns);
      ASSERT_GE(toward, prev - 1e-6f);  // more blend, closer to ns
      prev = toward;
    }
  }
}

}  // namespace
}  // namespace sylva
