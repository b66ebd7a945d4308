// Tests for the ground plane of `--ground` (core/scene/ground_plane.h): placed at the lowest
// point, a disc sized by the framing radius, role ground, ids, unchanged framing, and the empty
// scene.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/gl/depth_range.h"
#include "core/scene/ground_plane.h"

namespace sylva {
namespace {

// A thin upright triangle pair (a "trunk") from y = 1 to y = 5 around x = 2, z = -1.
Scene post() {
  Scene s;
  Mesh m;
  m.name = "trunk";
  m.positions = {
      {1.5f, 1.0f, -1.0f}, {2.5f, 1.0f, -1.0f}, {2.5f, 5.0f, -1.0f}, {1.5f, 5.0f, -1.0f}};
  m.normals.assign(4, glm::vec3(0, 0, 1));
  m.indices = {0, 1, 2, 0, 2, 3};
  m.primitive_ids = {1, 1};
  m.cluster_ids = {3, 3};
  m.roles = {Role::Wood, Role::Wood};
  s.meshes.push_back(m);
  return s;
}

TEST(GroundPlane, UnderTheLowestPointSizedByTheFramingRadius) {
  Scene s = post();
  const Sphere before = s.framing_sphere();
  add_ground_plane(s, glm::vec4(0.5f, 0.4f, 0.3f, 1.0f));
  ASSERT_EQ(s.meshes.size(), 2u);
  const Mesh& g = s.meshes[1];
  EXPECT_EQ(g.name, "sylva-ground");
  const size_t n = size_t(kGroundSegments);
  ASSERT_EQ(g.triangle_count(), n);
  EXPECT_EQ(g.roles, std::vector<Role>(n, Role::Ground));
  EXPECT_EQ(g.primitive_ids, std::vector<uint32_t>(n, 2));
  EXPECT_EQ(g.cluster_ids, std::vector<uint32_t>(n, 3));  // the non-foliage cluster
  // A disc: the centre under the framing sphere's, the rim at kGroundRadiusInRadii * R.
  const float radius = kGroundRadiusInRadii * before.radius;
  ASSERT_EQ(g.positions.size(), n + 1);
  EXPECT_EQ(g.positions[0], glm::vec3(before.centre.x, 1.0f, before.centre.z));
  for (size_t i = 0; i < g.positions.size(); ++i) {
    const glm::vec3& p = g.positions[i];
    EXPECT_EQ(p.y, 1.0f);
    if (i == 0) continue;
    EXPECT_NEAR(glm::length(glm::vec2(p.x - before.centre.x, p.z - before.centre.z)), radius,
                1e-5f * radius);
  }
  ASSERT_EQ(g.uvs.size(), g.positions.size());
  for (const glm::vec2& uv : g.uvs)
    EXPECT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f);
  for (const glm::vec3& nr : g.normals)
    EXPECT_EQ(nr, glm::vec3(0, 1, 0));
  // Every front face looks up, and the triangles tile the disc's polygon: their areas add up
  // to n/2 r^2 sin(2 pi / n).
  double area = 0.0;
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3 a = g.positions[g.indices[3 * t]], b = g.positions[g.indices[3 * t + 1]],
                    c = g.positions[g.indices[3 * t + 2]];
    const float up = glm::cross(b - a, c - a).y;
    EXPECT_GT(up, 0.0f) << t;
    area += 0.5 * double(up);
  }
  EXPECT_NEAR(
      area,
      0.5 * double(n) * double(radius) * radius * std::sin(2.0 * std::numbers::pi / double(n)),
      1e-4 * area);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(g.material, 0);
  EXPECT_EQ(s.materials[0].base_color, glm::vec4(0.5f, 0.4f, 0.3f, 1.0f));
  EXPECT_TRUE(s.materials[0].double_sided);
  // The framing ignores the ground, so the camera does not change.
  const Sphere after = s.framing_sphere();
  EXPECT_EQ(after.centre, before.centre);
  EXPECT_EQ(after.radius, before.radius);
}

TEST(GroundPlane, GroundAloneIsFramedAndEmptySceneGetsNone) {
  Scene empty;
  add_ground_plane(empty, glm::vec4(1.0f));
  EXPECT_TRUE(empty.meshes.empty());
  Scene s = post();
  s.meshes[0].roles = {Role::Ground, Role::Ground};
  const Sphere sphere = s.framing_sphere();  // only ground: it is framed
  EXPECT_FALSE(sphere.empty());
  EXPECT_GT(sphere.radius, 1.0f);
}

TEST(GroundPlane, ColourIsClampedAndFinite) {
  Scene s = post();
  add_ground_plane(s, glm::vec4(2.0f, -1.0f, 0.5f, 1.0f));
  EXPECT_EQ(s.materials.back().base_color, glm::vec4(1.0f, 0.0f, 0.5f, 1.0f));
}

// The orbit camera's depth range hugs the framing sphere, which leaves the ground out:
// fit_camera_depth widens it to hold the ground, and leaves scenes without ground alone.
TEST(GroundPlane, CameraDepthHoldsTheGround) {
  Scene s = post();
  for (bool ortho : {false, true}) {
    OrbitParams orbit;
    orbit.ortho = ortho;
    const Camera plain = make_orbit_camera(s.framing_sphere(), orbit, 32, 32);
    Camera same = plain;
    fit_camera_depth(same, s);
    EXPECT_EQ(same.proj, plain.proj);
    EXPECT_EQ(same.far_plane, plain.far_plane);
    Scene g = s;
    add_ground_plane(g, glm::vec4(1.0f));
    Camera cam = make_orbit_camera(g.framing_sphere(), orbit, 32, 32);
    EXPECT_EQ(cam.proj, plain.proj);  // the framing ignores the ground
    fit_camera_depth(cam, g);
    EXPECT_GE(cam.far_plane, plain.far_plane);
    EXPECT_LE(cam.near_plane, plain.near_plane);
    EXPECT_GE(cam.near_plane, cam.far_plane * 1e-3f * 0.999f);
    EXPECT_EQ(cam.proj[0][0], plain.proj[0][0]);  // same field of view / extent
    EXPECT_EQ(cam.proj[1][1], plain.proj[1][1]);
    // Every ground vertex in front of the camera lies within [near, far] and maps to NDC
    // depth in [-1, 1].
    for (const glm::vec3& p : g.meshes.back().positions) {
      const glm::vec4 v = cam.view * glm::vec4(p, 1.0f);
      if (-v.z <= cam.near_plane) continue;  // behind the near plane (under the camera)
      EXPECT_LE(-v.z, cam.far_plane);
      const glm::vec4 c = cam.proj * v;
      EXPECT_LE(c.z / c.w, 1.0f + 1e-5f) << ortho;
    }
  }
}

}  // namespace
}  // namespace sylva
