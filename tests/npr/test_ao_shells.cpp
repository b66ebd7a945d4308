#include "npr/ao_shells.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/error.h"

namespace sylva {
namespace {

std::vector<glm::vec3> random_in_ball(size_t n, glm::vec3 centre, float radius, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> out;
  while (out.size() < n) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    if (glm::dot(p, p) <= 1.0f) out.push_back(centre + radius * p);
  }
  return out;
}

std::vector<glm::vec3> random_on_sphere(size_t n, glm::vec3 centre, float radius, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<glm::vec3> out;
  while (out.size() < n) {
    const glm::vec3 p(g(rng), g(rng), g(rng));
    if (glm::length(p) > 1e-3f) out.push_back(centre + radius * glm::normalize(p));
  }
  return out;
}

bool inside(const Sphere& s, const glm::vec3& p) {
  return glm::length(p - s.centre) <= s.radius;
}

// |u| <= 1 for u = diag(1/radii) axes^T (p - centre), in float as a shader would.
bool inside(const Ellipsoid& e, const glm::vec3& p) {
  const glm::vec3 q = glm::transpose(e.axes) * (p - e.centre);
  const glm::vec3 u = q / e.radii;
  return glm::dot(u, u) <= 1.0f;
}

bool all_finite(const Ellipsoid& e) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(e.axes[i][j])) return false;
  return std::isfinite(e.centre.x + e.centre.y + e.centre.z) &&
         std::isfinite(e.radii.x + e.radii.y + e.radii.z);
}

TEST(BoundingSphere, SimpleSets) {
  Sphere s = fit_bounding_sphere({glm::vec3(1, 2, 3)});
  EXPECT_EQ(s.centre, glm::vec3(1, 2, 3));
  EXPECT_EQ(s.radius, 0.0f);
  s = fit_bounding_sphere({glm::vec3(-1, 0, 0), glm::vec3(3, 0, 0), glm::vec3(1, 0.5f, 0)});
  EXPECT_NEAR(s.centre.x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.radius, 2.0f, 1e-5f);
  // Regular tetrahedron with circumradius sqrt(3).
  s = fit_bounding_sphere(
      {glm::vec3(1, 1, 1), glm::vec3(1, -1, -1), glm::vec3(-1, 1, -1), glm::vec3(-1, -1, 1)});
  EXPECT_NEAR(glm::length(s.centre), 0.0f, 1e-6f);
  EXPECT_NEAR(s.radius, std::sqrt(3.0f), 1e-5f);
}

TEST(BoundingSphere, IsTheMinimalSphere) {
  // Points on a sphere (plus some inside) have that sphere as their minimal enclosing one;
  // Ritter's approximation would be up to ~5% too big here.
  for (uint32_t seed : {1u, 2u, 3u}) {
    const glm::vec3 c(10.0f * float(seed), -3.0f, 1e3f);
    std::vector<glm::vec3> pts = random_on_sphere(2000, c, 2.5f, seed);
    for (const glm::vec3& p : random_in_ball(3000, c, 2.4f, seed + 10))
      pts.push_back(p);
    const Sphere s = fit_bounding_sphere(pts);
    EXPECT_NEAR(s.radius, 2.5f, 2.5f * 2e-4f);
    EXPECT_NEAR(glm::length(s.centre - c), 0.0f, 2e-3f);
    for (const glm::vec3& p : pts)
      ASSERT_TRUE(inside(s, p));
  }
}

TEST(BoundingSphere, CoplanarAndDuplicatePoints) {
  // A ring in the plane z = 4, with many copies: the circle's sphere.
  std::vector<glm::vec3> pts;
  for (int i = 0; i < 500; ++i) {
    const float a = float(i) * 0.1f;
    for (int copy = 0; copy < 3; ++copy)
      pts.emplace_back(std::cos(a), std::sin(a), 4.0f);
  }
  const Sphere s = fit_bounding_sphere(pts);
  EXPECT_NEAR(s.radius, 1.0f, 1e-4f);
  EXPECT_NEAR(s.centre.z, 4.0f, 1e-5f);
  for (const glm::vec3& p : pts)
    EXPECT_TRUE(inside(s, p));
  // Collinear.
  const Sphere line = fit_bounding_sphere({glm::vec3(0), glm::vec3(1), glm::vec3(2), glm::vec3(5)});
  EXPECT_NEAR(line.radius, 2.5f * std::sqrt(3.0f), 1e-5f);
}

TEST(BoundingSphere, BadInput) {
  EXPECT_THROW(fit_bounding_sphere({}), InputError);
  EXPECT_THROW(fit_bounding_sphere({glm::vec3(0), glm::vec3(NAN, 0, 0)}), InputError);
  EXPECT_THROW(fit_bounding_ellipsoid({glm::vec3(INFINITY)}), InputError);
}

TEST(BoundingEllipsoid, AxisAlignedBox) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> pts;
  for (int i = 0; i < 5000; ++i)
    pts.emplace_back(1 + 4 * u(rng), 2 + 2 * u(rng), 3 + u(rng));
  const Ellipsoid e = fit_bounding_ellipsoid(pts);
  EXPECT_NEAR(std::abs(e.axes[0].x), 1.0f, 1e-2f);  // longest along x, then y, then z
  EXPECT_NEAR(std::abs(e.axes[1].y), 1.0f, 1e-2f);
  EXPECT_NEAR(std::abs(e.axes[2].z), 1.0f, 1e-2f);
  EXPECT_NEAR(glm::determinant(e.axes), 1.0f, 1e-5f);  // right-handed, orthonormal
  EXPECT_NEAR(glm::dot(e.axes[0], e.axes[1]), 0.0f, 1e-6f);
  EXPECT_GT(e.radii.x, e.radii.y);
  EXPECT_GT(e.radii.y, e.radii.z);
  EXPECT_NEAR(glm::length(e.centre - glm::vec3(1, 2, 3)), 0.0f, 0.05f);
  // Encloses the box's corners: the semi-axes are about sqrt(3) times the half extents.
  EXPECT_NEAR(e.radii.x / 4.0f, std::sqrt(3.0f), 0.1f);
  for (const glm::vec3& p : pts)
    ASSERT_TRUE(inside(e, p));
}

TEST(BoundingEllipsoid, RotatedCloudAndSphereCloud) {
  const glm::mat3 rot(glm::normalize(glm::vec3(1, 1, 0)), glm::normalize(glm::vec3(-1, 1, 0)),
                      glm::vec3(0, 0, 1));
  std::vector<glm::vec3> pts;
  for (const glm::vec3& p : random_in_ball(4000, glm::vec3(0), 1.0f, 5))
    pts.push_back(glm::vec3(-7, 0, 2) + rot * (p * glm::vec3(5, 1, 0.5f)));
  const Ellipsoid e = fit_bounding_ellipsoid(pts);
  EXPECT_GT(std::abs(glm::dot(e.axes[0], rot[0])), 0.999f);
  EXPECT_NEAR(e.radii.x, 5.0f, 0.5f);
  EXPECT_NEAR(e.radii.z, 0.5f, 0.1f);
  for (const glm::vec3& p : pts)
    ASSERT_TRUE(inside(e, p));
  // A filled ball: close to its bounding sphere.
  const auto ball = random_in_ball(4000, glm::vec3(3), 2.0f, 6);
  const Ellipsoid b = fit_bounding_ellipsoid(ball);
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(b.radii[a], 2.0f, 0.25f);
}

TEST(BoundingEllipsoid, CoplanarCollinearAndSinglePoint) {
  std::vector<glm::vec3> plane;  // all leaves coplanar (z = 1)
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 20; ++j)
      plane.emplace_back(0.1f * float(i), 0.1f * float(j), 1.0f);
  const Ellipsoid e = fit_bounding_ellipsoid(plane);
  EXPECT_TRUE(all_finite(e));
  EXPECT_GT(e.radii.z, 0.0f);
  EXPECT_NEAR(e.radii.z / e.radii.x, kMinEllipsoidAxisRatio, 1e-4f);
  EXPECT_NEAR(std::abs(e.axes[2].z), 1.0f, 1e-5f);
  for (const glm::vec3& p : plane)
    EXPECT_TRUE(inside(e, p));
  const Sphere s = fit_bounding_sphere(plane);
  EXPECT_TRUE(std::isfinite(s.radius) && s.radius > 0.0f);

  const Ellipsoid line =
      fit_bounding_ellipsoid({glm::vec3(0), glm::vec3(1, 1, 0), glm::vec3(3, 3, 0)});
  EXPECT_TRUE(all_finite(line));
  EXPECT_NEAR(line.radii.y / line.radii.x, kMinEllipsoidAxisRatio, 1e-4f);
  EXPECT_NEAR(line.radii.z / line.radii.x, kMinEllipsoidAxisRatio, 1e-4f);

  const Ellipsoid point = fit_bounding_ellipsoid({glm::vec3(2, 3, 4), glm::vec3(2, 3, 4)});
  EXPECT_EQ(point.centre, glm::vec3(2, 3, 4));
  EXPECT_EQ(point.radii, glm::vec3(0.0f));
}

// Two blobs far apart plus a third small one.
std::vector<glm::vec3> three_blobs() {
  std::vector<glm::vec3> pts = random_in_ball(3000, glm::vec3(-10, 0, 0), 2.0f, 11);
  for (const glm::vec3& p : random_in_ball(2000, glm::vec3(10, 0, 0), 3.0f, 12))
    pts.push_back(p);
  for (const glm::vec3& p : random_in_ball(500, glm::vec3(0, 15, 0), 1.0f, 13))
    pts.push_back(p);
  return pts;
}

TEST(Shells, EveryVertexUsesAShellThatEnclosesIt) {
  const auto pts = three_blobs();
  for (ShellKind kind : {ShellKind::Sphere, ShellKind::Ellipsoid})
    for (int k : {1, 2, 3, 7, 64}) {
      const Shells s = fit_shells(pts, ShellOptions{k, kind, 1});
      ASSERT_EQ(s.shells.size(), size_t(k));
      ASSERT_EQ(s.anchors.size(), s.shells.size());
      ASSERT_EQ(s.labels.size(), pts.size());
      for (size_t i = 0; i < pts.size(); ++i) {
        ASSERT_EQ(s.nearest(pts[i]), s.labels[i]);
        ASSERT_TRUE(inside(s.shells[s.labels[i]], pts[i])) << k << " " << i;
      }
    }
}

TEST(Shells, FindsSeparatedBlobs) {
  const auto pts = three_blobs();
  const Shells s = fit_shells(pts, ShellOptions{3, ShellKind::Sphere, 4});
  std::vector<float> radii;
  for (const Ellipsoid& e : s.shells)
    radii.push_back(e.radii.x);
  std::sort(radii.begin(), radii.end());
  EXPECT_NEAR(radii[0], 1.0f, 0.05f);
  EXPECT_NEAR(radii[1], 2.0f, 0.1f);
  EXPECT_NEAR(radii[2], 3.0f, 0.1f);
  EXPECT_EQ(s.labels[0], s.labels[2999]);
  EXPECT_NE(s.labels[0], s.labels[3000]);
}

TEST(Shells, OneShellIsTheBoundingShell) {
  const auto pts = random_in_ball(3000, glm::vec3(1, 2, 3), 4.0f, 21);
  const Shells s = fit_shells(pts, ShellOptions{1, ShellKind::Sphere, 9});
  const Sphere b = fit_bounding_sphere(pts);
  ASSERT_EQ(s.shells.size(), 1u);
  EXPECT_EQ(s.shells[0].centre, b.centre);
  EXPECT_EQ(s.shells[0].radii, glm::vec3(b.radius));
  const Shells e = fit_shells(pts, ShellOptions{1, ShellKind::Ellipsoid, 9});
  EXPECT_EQ(e.shells[0].radii, fit_bounding_ellipsoid(pts).radii);
}

TEST(Shells, KClampsToTheDistinctPoints) {
  // Three leaves whose vertices repeat (unindexed triangles): 5 distinct positions.
  std::vector<glm::vec3> pts;
  for (int r = 0; r < 4; ++r)
    for (const glm::vec3& p : {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                               glm::vec3(5, 5, 5), glm::vec3(5, 6, 5)})
      pts.push_back(p);
  const Shells s = fit_shells(pts, ShellOptions{64, ShellKind::Sphere, 1});
  ASSERT_EQ(s.shells.size(), 5u);
  for (size_t i = 0; i < pts.size(); ++i) {
    EXPECT_EQ(s.shells[s.labels[i]].radii, glm::vec3(0.0f));  // one point per shell
    EXPECT_EQ(s.anchors[s.labels[i]], pts[i]);
  }
  const Shells one = fit_shells({glm::vec3(1, 2, 3)}, ShellOptions{8, ShellKind::Ellipsoid, 1});
  ASSERT_EQ(one.shells.size(), 1u);
  EXPECT_TRUE(all_finite(one.shells[0]));
}

TEST(Shells, CoplanarLeavesStayFinite) {
  std::vector<glm::vec3> pts;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j)
      pts.emplace_back(0.05f * float(i), 2.0f, 0.05f * float(j));
  for (ShellKind kind : {ShellKind::Sphere, ShellKind::Ellipsoid}) {
    const Shells s = fit_shells(pts, ShellOptions{6, kind, 2});
    for (const Ellipsoid& e : s.shells) {
      EXPECT_TRUE(all_finite(e));
      EXPECT_GT(e.radii.x * e.radii.y * e.radii.z, 0.0f);
    }
  }
}

TEST(Shells, DeterministicAndSeeded) {
  const auto pts = random_in_ball(30000, glm::vec3(0), 5.0f, 31);  // above the sample limit
  const Shells a = fit_shells(pts, ShellOptions{12, ShellKind::Ellipsoid, 5});
  const Shells b = fit_shells(pts, ShellOptions{12, ShellKind::Ellipsoid, 5});
  ASSERT_EQ(a.shells.size(), b.shells.size());
  EXPECT_EQ(0, std::memcmp(a.shells.data(), b.shells.data(), a.shells.size() * sizeof(Ellipsoid)));
  EXPECT_EQ(a.labels, b.labels);
  const Shells c = fit_shells(pts, ShellOptions{12, ShellKind::Ellipsoid, 6});
  EXPECT_NE(a.labels, c.labels);
  for (size_t i = 0; i < pts.size(); ++i)
    ASSERT_TRUE(inside(a.shells[a.labels[i]], pts[i]));
}

TEST(Shells, Validation) {
  const std::vector<glm::vec3> pts{glm::vec3(0), glm::vec3(1)};
  EXPECT_THROW(fit_shells(pts, ShellOptions{0, ShellKind::Sphere, 1}), InputError);
  EXPECT_THROW(fit_shells(pts, ShellOptions{65, ShellKind::Sphere, 1}), InputError);
  EXPECT_NO_THROW(fit_shells(pts, ShellOptions{64, ShellKind::Sphere, 1}));
  EXPECT_THROW(fit_shells({}, ShellOptions{}), InputError);
  EXPECT_THROW(fit_shells({glm::vec3(NAN)}, ShellOptions{}), InputError);
  try {
    validate_shell_options(ShellOptions{100, ShellKind::Sphere, 1});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "ao-shells");
  }
}

}  // namespace
}  // namespace sylva
