// The OpenMesh surface optimisation of marching-cubes meshes: smoothing, decimation, their
// extremes and invalid options, determinism.
#include <gtest/gtest.h>

#include <random>

#include "core/error.h"
#include "npr/implicit_surface.h"
#include "tests/npr/mesh_checks.h"

namespace sylva {
namespace {

using namespace mesh_checks;

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
