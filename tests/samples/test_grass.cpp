// Tests for the procedural grass patch (samples/grass.h): counts, roles, bounds, unit
// normals, determinism, the blade-count range at both ends and just outside, and the grass
// role surviving a .glb round trip.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "samples/grass.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

Scene grass(int blades, uint64_t seed = 1) {
  GrassOptions o;
  o.blades = blades;
  o.seed = seed;
  return make_grass(o);
}

TEST(Grass, BladesStandOnTheGroundWithGrassRole) {
  const Scene s = grass(500);
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "grass");
  EXPECT_EQ(m.triangle_count(), 3u * 500u);
  EXPECT_EQ(m.positions.size(), 5u * 500u);
  ASSERT_EQ(m.roles.size(), m.triangle_count());
  ASSERT_EQ(m.primitive_ids.size(), m.triangle_count());
  ASSERT_EQ(m.cluster_ids.size(), m.triangle_count());
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    EXPECT_EQ(m.roles[t], Role::Grass);
    EXPECT_EQ(m.primitive_ids[t], t / 3 + 1);
  }
  const Bounds b = s.bounds();
  EXPECT_EQ(b.min.y, 0.0f);
  EXPECT_LE(b.max.y, kGrassHeight);
  EXPECT_GT(b.max.y, 0.9f * kGrassHeight);
  EXPECT_GE(b.min.x, -0.5f * kGrassPatchSide - kGrassBladeWidth - kGrassHeight);
  EXPECT_LE(b.max.x, 0.5f * kGrassPatchSide + kGrassBladeWidth + kGrassHeight);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const glm::vec3& n : m.normals) {
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
  }
  // Each blade's front face agrees with its vertex normals.
  for (size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b2 = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b2 - a, c - a), m.normals[m.indices[3 * t]]), 0.0f) << t;
  }
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_TRUE(s.materials[0].double_sided);
}

TEST(Grass, DeterministicPerSeed) {
  const Scene a = grass(200, 7), b = grass(200, 7), c = grass(200, 8);
  EXPECT_EQ(a.meshes[0].positions, b.meshes[0].positions);
  EXPECT_EQ(a.meshes[0].normals, b.meshes[0].normals);
  EXPECT_NE(a.meshes[0].positions, c.meshes[0].positions);
}

TEST(Grass, BladeCountRange) {
  EXPECT_EQ(grass(kMinGrassBlades).triangle_count(), 3u);
  EXPECT_EQ(grass(kMaxGrassBlades).triangle_count(), 3u * size_t(kMaxGrassBlades));
  EXPECT_EQ(test::where_of([] { grass(kMinGrassBlades - 1); }), "--blades");
  EXPECT_EQ(test::where_of([] { grass(kMaxGrassBlades + 1); }), "--blades");
  EXPECT_EQ(test::where_of([] { grass(-5); }), "--blades");
}

TEST(Grass, RoleSurvivesGlb) {
  const std::string path = test::temp_dir("grass") + "/grass.glb";
  write_glb(grass(50), path);
  const Scene s = load_scene(path);
  size_t grass_triangles = 0;
  for (const Mesh& m : s.meshes)
    for (Role r : m.roles)
      grass_triangles += r == Role::Grass;
  EXPECT_EQ(grass_triangles, 150u);
  EXPECT_TRUE(s.bounds(Role::Foliage).empty());
  EXPECT_EQ(s.bounds(Role::Grass).min.y, 0.0f);
}

TEST(Grass, NamedMeshesAreGrassWithoutExtras) {
  Scene s = grass(10);
  s.meshes[0].roles.clear();
  LoadOptions o;
  finish_scene(s, o, false);
  ASSERT_EQ(s.meshes[0].roles.size(), 30u);
  EXPECT_EQ(s.meshes[0].roles[0], Role::Grass);
}

}  // namespace
}  // namespace sylva
