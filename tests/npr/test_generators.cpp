// Generator points (Luft et al. §3.1): one per leaf at its area-weighted centroid, or one
// per foliage triangle; the seeded fraction (range, rounding, determinism); no foliage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "npr/generators.h"
#include "samples/plants.h"

namespace sylva {
namespace {

Scene tree(int leaves, uint64_t seed = 1) {
  PlantOptions o;
  o.kind = PlantKind::Tree;
  o.leaves = leaves;
  o.seed = seed;
  return make_plant(o);
}

size_t foliage_triangles(const Scene& s) {
  size_t n = 0;
  for (const Mesh& m : s.meshes)
    n += size_t(std::count(m.roles.begin(), m.roles.end(), Role::Foliage));
  return n;
}

// One mesh of the given role holding the triangles, each its own primitive unless `ids`
// says otherwise.
Mesh mesh_of(std::vector<glm::vec3> positions, std::vector<uint32_t> indices,
             std::vector<uint32_t> ids, Role role) {
  Mesh m;
  m.positions = std::move(positions);
  m.indices = std::move(indices);
  m.primitive_ids = std::move(ids);
  m.roles.assign(m.triangle_count(), role);
  m.cluster_ids.assign(m.triangle_count(), 1);
  return m;
}

// A trapezoid-like quad whose area-weighted centroid (5/6, 13/12, 0) differs from the mean
// of its corners (1, 1, 0): triangle (0,1,2) has area 1, centroid (4/3, 1/3); triangle
// (0,2,3) has area 3, centroid (2/3, 4/3).
Mesh quad(uint32_t id, float z = 0.0f) {
  return mesh_of({{0, 0, z}, {2, 0, z}, {2, 1, z}, {0, 3, z}}, {0, 1, 2, 0, 2, 3}, {id, id},
                 Role::Foliage);
}

TEST(Generators, OnePerLeafOnASampleTree) {
  Scene s = tree(500);
  std::vector<glm::vec3> g = make_generators(s, {});
  EXPECT_EQ(g.size(), 500u);
  // Leaf k (primitive id k + 1) is the quad of foliage triangles 2k, 2k + 1: its generator
  // lies inside the leaf's bounding box.
  const Mesh& leaves = s.meshes[0];
  ASSERT_EQ(leaves.roles[0], Role::Foliage);
  for (size_t k = 0; k < g.size(); ++k) {
    Bounds b;
    for (size_t t = 2 * k; t < 2 * k + 2; ++t) {
      ASSERT_EQ(leaves.primitive_ids[t], k + 1);
      for (int c = 0; c < 3; ++c)
        b.extend(leaves.positions[leaves.indices[3 * t + c]]);
    }
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(g[k][a], b.min[a] - 1e-5f);
      EXPECT_LE(g[k][a], b.max[a] + 1e-5f);
    }
  }
  EXPECT_EQ(make_generators(s, {1.0, true}).size(), foliage_triangles(s));
  EXPECT_EQ(foliage_triangles(s), 1000u);
}

TEST(Generators, AreaWeightedCentroidOfAQuad) {
  Scene s;
  s.meshes = {mesh_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {1}, Role::Wood), quad(2)};
  std::vector<glm::vec3> g = make_generators(s, {});
  ASSERT_EQ(g.size(), 1u);
  EXPECT_NEAR(g[0].x, 5.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(g[0].y, 13.0f / 12.0f, 1e-6f);
  EXPECT_NEAR(g[0].z, 0.0f, 1e-6f);

  GeneratorOptions per_triangle;
  per_triangle.per_triangle = true;
  g = make_generators(s, per_triangle);
  ASSERT_EQ(g.size(), 2u);
  EXPECT_NEAR(g[0].x, 4.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(g[0].y, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(g[1].x, 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(g[1].y, 4.0f / 3.0f, 1e-6f);
}

TEST(Generators, ZeroAreaPrimitiveFallsBackToVertexMean) {
  Scene s;
  // Primitive 1: collinear corners, no area, so the centre is the mean of the corners.
  // Primitive 2: the quad plus a degenerate sliver, which has no weight.
  // Primitive 3: two collinear triangles (corners counted per triangle).
  Mesh m = mesh_of({{0, 0, 0}, {1, 0, 0}, {5, 0, 0}}, {0, 1, 2}, {1}, Role::Foliage);
  Mesh q = quad(2, 1.0f);
  q.positions.push_back({100, 0, 1});
  q.indices.insert(q.indices.end(), {0, 1, 4});  // (0,0,1), (2,0,1), (100,0,1): collinear
  q.primitive_ids.push_back(2);
  q.roles.push_back(Role::Foliage);
  Mesh line = mesh_of({{0, 0, 2}, {0, 3, 2}, {0, 6, 2}, {0, 9, 2}}, {0, 1, 2, 1, 2, 3}, {3, 3},
                      Role::Foliage);
  s.meshes = {m, q, line};
  std::vector<glm::vec3> g = make_generators(s, {});
  ASSERT_EQ(g.size(), 3u);
  EXPECT_NEAR(g[0].x, 2.0f, 1e-6f);
  EXPECT_NEAR(g[0].y, 0.0f, 1e-6f);
  EXPECT_NEAR(g[1].x, 5.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(g[1].y, 13.0f / 12.0f, 1e-6f);
  EXPECT_NEAR(g[1].z, 1.0f, 1e-6f);
  EXPECT_NEAR(g[2].y, 4.5f, 1e-6f);  // (0 + 3 + 6 + 3 + 6 + 9) / 6
  EXPECT_NEAR(g[2].z, 2.0f, 1e-6f);
}

TEST(Generators, PrimitiveIdOrderAcrossMeshesAndSparseIds) {
  Scene s;
  // Ids out of mesh order and far apart (not dense): output follows the ids.
  s.meshes = {quad(4'000'000'000u, 3.0f), quad(7, 1.0f), quad(900'000, 2.0f)};
  std::vector<glm::vec3> g = make_generators(s, {});
  ASSERT_EQ(g.size(), 3u);
  EXPECT_FLOAT_EQ(g[0].z, 1.0f);
  EXPECT_FLOAT_EQ(g[1].z, 2.0f);
  EXPECT_FLOAT_EQ(g[2].z, 3.0f);
}

TEST(Generators, FractionKeepsRoundedShare) {
  Scene s = tree(1000);
  const std::vector<glm::vec3> all = make_generators(s, {});
  ASSERT_EQ(all.size(), 1000u);
  GeneratorOptions o;
  o.fraction = 0.5;
  std::vector<glm::vec3> half = make_generators(s, o);
  EXPECT_EQ(half.size(), 500u);
  // A subset of all generators, in primitive-id order.
  size_t j = 0;
  for (const glm::vec3& p : half) {
    while (j < all.size() && all[j] != p)
      ++j;
    ASSERT_LT(j, all.size()) << "not an in-order subset";
    ++j;
  }
  o.fraction = 0.3337;
  EXPECT_EQ(make_generators(s, o).size(), 334u);
  o.fraction = 1e-9;  // rounds to 0, but at least one is kept
  EXPECT_EQ(make_generators(s, o).size(), 1u);
  o.fraction = 1.0;
  EXPECT_EQ(make_generators(s, o), all);
  o.per_triangle = true;
  o.fraction = 0.25;
  EXPECT_EQ(make_generators(s, o).size(), 500u);
}

TEST(Generators, FractionOutOfRangeThrows) {
  Scene s = tree(100);
  for (double f : {0.0, -0.5, 1.0000001, 2.0, double(NAN), double(INFINITY)}) {
    GeneratorOptions o;
    o.fraction = f;
    try {
      make_generators(s, o);
      ADD_FAILURE() << "fraction " << f << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "fraction");
    }
  }
}

TEST(Generators, SeedSelectsSubsetDeterministically) {
  Scene s = tree(1000);
  GeneratorOptions o;
  o.fraction = 0.2;
  o.seed = 42;
  const std::vector<glm::vec3> a = make_generators(s, o);
  EXPECT_EQ(make_generators(s, o), a);
  o.seed = 43;
  const std::vector<glm::vec3> b = make_generators(s, o);
  EXPECT_EQ(b.size(), a.size());
  EXPECT_NE(b, a);
}

TEST(Generators, NoFoliageGivesNone) {
  Scene s;
  s.meshes = {mesh_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, {1}, Role::Wood)};
  EXPECT_TRUE(make_generators(s, {}).empty());
  GeneratorOptions o;
  o.per_triangle = true;
  o.fraction = 0.1;
  EXPECT_TRUE(make_generators(s, o).empty());
  EXPECT_TRUE(make_generators(Scene{}, {}).empty());
}

}  // namespace
}  // namespace sylva
