// Loading real and small scenes: the shared fern, in-memory scenes through finish_scene,
// foliage rules, primitive ids, degenerate triangles, and the polygon mesh formats.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/scene/components.h"
#include "core/scene/foliage.h"
#include "core/scene/load.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

// A unit quad (two triangles) at height z, offset along x.
Mesh quad(const std::string& name, float x, float z = 0.0f, int material = -1) {
  Mesh m;
  m.name = name;
  m.material = material;
  m.positions = {{x, 0, z}, {x + 1, 0, z}, {x + 1, 1, z}, {x, 1, z}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Material material(const std::string& name, AlphaMode mode = AlphaMode::Opaque) {
  Material m;
  m.name = name;
  m.alpha_mode = mode;
  return m;
}

TEST(LoadFern, TrianglesBoundsTextureRoles) {
  Scene s = load_scene(test::fern_path());
  EXPECT_EQ(s.triangle_count(), 6232u);
  EXPECT_EQ(s.meshes.size(), 4u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "fern_02");
  EXPECT_EQ(s.materials[0].alpha_mode, AlphaMode::Mask);
  EXPECT_TRUE(s.materials[0].double_sided);
  EXPECT_EQ(s.report.source, test::fern_path());
  EXPECT_EQ(s.report.dropped_degenerate, 0u);
  const Bounds b = s.bounds();
  ASSERT_FALSE(b.empty());
  EXPECT_TRUE(std::isfinite(b.diagonal()));
  EXPECT_GT(b.diagonal(), 0.5f);
  // The node translations (about 1 unit in x and z) are applied: the four ferns spread out.
  EXPECT_GT(b.max.x, 1.2f);
  EXPECT_GT(b.max.z, 1.2f);

  ASSERT_EQ(s.textures.size(), 1u);  // only the base colour is decoded
  const Texture& t = s.textures[size_t(s.materials[0].base_color_texture)];
  EXPECT_EQ(t.width, 2048);
  EXPECT_EQ(t.height, 2048);
  ASSERT_EQ(t.rgba.size(), size_t(2048) * 2048 * 4);
  // The asset's base colour is a 3-channel JPEG: alpha decodes as opaque everywhere.
  EXPECT_EQ(t.rgba[3], 255);
  bool warned = false;
  for (const std::string& w : s.report.warnings)
    warned = warned ||
             (w.find("fern_02") != std::string::npos && w.find("no alpha") != std::string::npos);
  EXPECT_TRUE(warned);

  EXPECT_EQ(s.report.foliage_rule, "alpha MASK");
  EXPECT_NE(s.report.foliage_reason.find("fern_02"), std::string::npos);
  for (const Mesh& m : s.meshes) {
    ASSERT_EQ(m.roles.size(), m.triangle_count());
    ASSERT_EQ(m.primitive_ids.size(), m.triangle_count());
    ASSERT_EQ(m.cluster_ids.size(), m.triangle_count());
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    for (Role r : m.roles)
      EXPECT_EQ(r, Role::Foliage);
    for (const glm::vec3& n : m.normals)
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  }
  EXPECT_GE(s.max_primitive_id(), 4u);
  EXPECT_EQ(s.max_cluster_id(), 1u);
}

TEST(LoadFern, FoliageOptions) {
  Scene none = load_scene(test::fern_path(), {"none"});
  EXPECT_EQ(none.report.foliage_rule, "--foliage none");
  EXPECT_TRUE(none.bounds(Role::Foliage).empty());
  Scene glob = load_scene(test::fern_path(), {"FERN_0?"});
  EXPECT_FALSE(glob.bounds(Role::Foliage).empty());
  Scene mesh_glob = load_scene(test::fern_path(), {"plane.02*"});
  EXPECT_EQ(mesh_glob.meshes[0].roles[0], Role::Foliage);  // Plane.024
  EXPECT_EQ(mesh_glob.meshes[1].roles[0], Role::Other);    // Plane.044
  try {
    load_scene(test::fern_path(), {"*bark*"});
    FAIL() << "no-match glob accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "--foliage");
    EXPECT_NE(std::string(e.what()).find("fern_02"), std::string::npos) << e.what();
  }
}

TEST(Foliage, RulesOnSmallScenes) {
  Scene s;
  s.materials = {material("Bark"), material("LeafMat"), material("ground_mat")};
  s.meshes = {quad("trunk", 0, 0, 0), quad("crown", 2, 0, 1), quad("floor", 4, 0, 2), quad("x", 6)};
  finish_scene(s, {});
  EXPECT_EQ(s.report.foliage_rule, "name match");
  EXPECT_EQ(s.meshes[0].roles[0], Role::Wood);
  EXPECT_EQ(s.meshes[1].roles[0], Role::Foliage);
  EXPECT_EQ(s.meshes[2].roles[0], Role::Ground);
  EXPECT_EQ(s.meshes[3].roles[0], Role::Other);
  classify_roles(s, "all");
  for (const Mesh& m : s.meshes)
    EXPECT_EQ(m.roles[0], Role::Foliage);
  classify_roles(s, "none");
  EXPECT_TRUE(s.bounds(Role::Foliage).empty());
  EXPECT_EQ(s.meshes[0].roles[0], Role::Wood);
  classify_roles(s, "Cr*n");
  EXPECT_EQ(s.meshes[1].roles[0], Role::Foliage);
  EXPECT_EQ(s.meshes[0].roles[0], Role::Wood);
  EXPECT_THROW(classify_roles(s, "nothing*"), InputError);
}

TEST(Foliage, FileRolesWinOnlyInAuto) {
  Scene s;
  s.materials = {material("LeafMat")};
  s.meshes = {quad("a", 0, 0, 0)};
  s.meshes[0].roles = {Role::Wood, Role::Wood};
  classify_roles(s, "auto");
  EXPECT_EQ(s.report.foliage_rule, "sylva_role extras");
  EXPECT_EQ(s.meshes[0].roles[0], Role::Wood);
  classify_roles(s, "all");
  EXPECT_EQ(s.meshes[0].roles[0], Role::Foliage);
}

TEST(Foliage, Glob) {
  EXPECT_TRUE(glob_match("*leaf*", "MyLEAFs"));
  EXPECT_TRUE(glob_match("fern_0?", "fern_02"));
  EXPECT_FALSE(glob_match("fern_0?", "fern_023"));
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_FALSE(glob_match("a*b*c", "aXbY"));
  EXPECT_TRUE(glob_match("a*b*c", "aXbYc"));
  EXPECT_FALSE(glob_match(std::string(200, '*') + "x", std::string(10000, 'a')));  // no blow-up
}

TEST(Components, DisjointAndSharedQuads) {
  Scene s;
  Mesh two = quad("two", 0);
  Mesh other = quad("b", 3);
  for (const glm::vec3& p : other.positions)
    two.positions.push_back(p);
  for (uint32_t i : other.indices)
    two.indices.push_back(i + 4);
  s.meshes = {two, quad("c", 6)};
  assign_primitive_ids(s);
  EXPECT_EQ(s.meshes[0].primitive_ids, (std::vector<uint32_t>{1, 1, 2, 2}));
  EXPECT_EQ(s.meshes[1].primitive_ids, (std::vector<uint32_t>{3, 3}));
}

TEST(Components, TwoMillionTriangles) {
  // Disjoint triangles in one mesh: the worst case for the id count.
  Scene s;
  Mesh m;
  const uint32_t n = 2'000'000;
  m.positions.resize(size_t(n) * 3);
  m.indices.resize(size_t(n) * 3);
  for (uint32_t i = 0; i < 3 * n; ++i)
    m.indices[i] = i;
  s.meshes.push_back(std::move(m));
  assign_primitive_ids(s);
  EXPECT_EQ(s.meshes[0].primitive_ids.size(), n);
  EXPECT_EQ(s.max_primitive_id(), n);
  EXPECT_EQ(s.meshes[0].primitive_ids.back(), n);
}

TEST(FinishScene, DegenerateTrianglesDroppedAndCounted) {
  Scene s;
  Mesh m = quad("q", 0);
  m.positions.push_back({0.5f, 0.5f, 0});
  m.indices.insert(m.indices.end(), {0, 0, 1});  // repeated index
  m.indices.insert(m.indices.end(), {0, 1, 4});  // collinear? no: (0.5,0.5) is off the edge
  m.indices.insert(m.indices.end(), {0, 2, 4});  // zero area: 4 lies on the 0-2 diagonal
  s.meshes = {m, quad("flat", 2)};
  s.meshes[1].positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};  // all collinear
  finish_scene(s, {});
  EXPECT_EQ(s.report.dropped_degenerate, 4u);
  ASSERT_EQ(s.meshes.size(), 1u);  // the all-degenerate mesh is gone
  EXPECT_EQ(s.meshes[0].triangle_count(), 3u);
  EXPECT_EQ(s.meshes[0].cluster_ids, (std::vector<uint32_t>{1, 1, 1}));
}

TEST(FinishScene, NormalsRepairedAndComputed) {
  Scene s;
  s.meshes = {quad("q", 0)};
  s.meshes[0].normals = {{0, 0, 2}, {NAN, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  finish_scene(s, {});
  for (const glm::vec3& n : s.meshes[0].normals) {
    EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
  }
  Scene t;
  t.meshes = {quad("q", 0)};
  finish_scene(t, {});
  ASSERT_EQ(t.meshes[0].normals.size(), 4u);
  EXPECT_NEAR(t.meshes[0].normals[0].z, 1.0f, 1e-6f);
}

TEST(FinishScene, BadInMemoryScenes) {
  Scene empty;
  EXPECT_THROW(finish_scene(empty, {}), InputError);
  Scene bad_index;
  bad_index.meshes = {quad("q", 0)};
  bad_index.meshes[0].indices[2] = 9;
  EXPECT_THROW(finish_scene(bad_index, {}), InputError);
  Scene nan;
  nan.meshes = {quad("q", 0)};
  nan.meshes[0].positions[1].y = INFINITY;
  EXPECT_THROW(finish_scene(nan, {}), InputError);
  Scene bad_h;
  bad_h.meshes = {quad("q", 0)};
  bad_h.hierarchy.branch_parent = {1, 0};  // a cycle
  bad_h.hierarchy.branch_diameter = {1, 1};
  EXPECT_THROW(finish_scene(bad_h, {}), InputError);
}

TEST(FinishScene, KeepRoles) {
  Scene s;
  s.meshes = {quad("leaf", 0)};
  s.meshes[0].roles = {Role::Ground, Role::Ground};
  finish_scene(s, {}, true);
  EXPECT_EQ(s.meshes[0].roles[0], Role::Ground);
}

// A unit cube in the four polygon mesh formats, written by hand.
const char* kCubeObj =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
const char* kCubeOff =
    "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
const char* kCubePly =
    "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
    "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

std::string cube_stl() {
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const float v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::string s = "solid cube\n";
  for (const auto& q : quads) {
    for (int t = 0; t < 2; ++t) {
      const int tri[3] = {q[0], q[1 + t], q[2 + t]};
      s += " facet normal 0 0 0\n  outer loop\n";
      for (int k : tri)
        s += "   vertex " + std::to_string(v[k][0]) + " " + std::to_string(v[k][1]) + " " +
             std::to_string(v[k][2]) + "\n";
      s += "  endloop\n endfacet\n";
    }
  }
  return s + "endsolid cube\n";
}

TEST(LoadMeshFiles, CubeInEveryFormat) {
  const std::string dir = test::temp_dir("cube");
  const std::pair<std::string, std::string> files[] = {{"cube.obj", kCubeObj},
                                                       {"cube.OFF", kCubeOff},
                                                       {"cube.ply", kCubePly},
                                                       {"cube.stl", cube_stl()}};
  for (const auto& [name, text] : files) {
    const std::string path = dir + "/" + name;
    test::write_file(path, text);
    Scene s = load_scene(path);
    ASSERT_EQ(s.meshes.size(), 1u) << name;
    EXPECT_EQ(s.meshes[0].name, "cube") << name;
    EXPECT_EQ(s.triangle_count(), 12u) << name;
    EXPECT_EQ(s.max_primitive_id(), 1u) << name;  // one closed surface
    EXPECT_NEAR(s.bounds().diagonal(), std::sqrt(3.0f), 1e-5f) << name;
    EXPECT_EQ(s.report.foliage_rule, "no foliage found") << name;
    for (const glm::vec3& n : s.meshes[0].normals)
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f) << name;
  }
}

// A number too large for a float and a word that is not a finite number ("nan") are errors
// (more in test_obj_strict.cpp).
TEST(LoadMeshFiles, InfiniteVertexIsAnError) {
  const std::string path = test::temp_dir("nan") + "/bad.obj";
  test::write_file(path, "v 0 0 0\nv 1 0 0\nv 1e39 1 0\nf 1 2 3\n");
  EXPECT_THROW(load_scene(path), InputError);
  test::write_file(path, "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  EXPECT_THROW(load_scene(path), InputError);
}

}  // namespace
}  // namespace sylva
