// Levels of detail (npr/plant_lod.h): each level about half the triangles of the one before,
// every vertex and triangle naming a real source, kept leaves nested across levels and
// enlarged by sqrt(2) per level about their centres, deterministic, and cached per plant;
// per-plant preprocessing of an instanced scene equals each plant's own.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

#include "core/scene/instances.h"
#include "npr/foliage_cache.h"
#include "npr/leaf_clusters.h"
#include "npr/plant_lod.h"
#include "samples/plants.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

const Scene& tree() {
  static const Scene s = [] {
    PlantOptions o;
    o.leaves = 1200;
    o.seed = 4;
    return make_plant(o);
  }();
  return s;
}

// The leaves (primitive ids) a level keeps of mesh k.
std::set<uint32_t> kept_leaves(const LodMesh& lod, const Mesh& m) {
  std::set<uint32_t> ids;
  for (uint32_t t : lod.triangle_source)
    if (m.roles[t] == Role::Foliage) ids.insert(m.primitive_ids[t]);
  return ids;
}

// Triangles of one role at a level.
size_t triangles(const std::vector<LodMesh>& level, const Scene& s, Role role) {
  size_t n = 0;
  for (size_t k = 0; k < level.size(); ++k)
    for (uint32_t t : level[k].triangle_source)
      n += s.meshes[k].roles[t] == role;
  return n;
}

// The leaves halve at every level; the wood halves until edge collapses can no longer keep
// each branch a closed tube (a floor of a few triangles per branch), and never grows.
TEST(PlantLod, EachLevelHalvesTheTrianglesFromRealSources) {
  const Scene& s = tree();
  const PlantLod lod = make_plant_lod(s);
  ASSERT_EQ(lod.levels.size(), size_t(kLodLevels));
  size_t leaves = 0;
  for (const Mesh& m : s.meshes)
    for (Role r : m.roles)
      leaves += r == Role::Foliage;
  size_t wood = s.triangle_count() - leaves;
  for (size_t l = 0; l < lod.levels.size(); ++l) {
    const std::vector<LodMesh>& level = lod.levels[l];
    ASSERT_EQ(level.size(), s.meshes.size());
    const size_t f = triangles(level, s, Role::Foliage), w = triangles(level, s, Role::Wood);
    EXPECT_NEAR(double(f), 0.5 * double(leaves), 0.2 * double(leaves) + 4.0) << "level " << l + 1;
    EXPECT_LE(w, wood);
    EXPECT_TRUE(l > 0 || double(w) <= 0.55 * double(wood)) << "first level of wood";
    leaves = f;
    wood = w;
    for (size_t k = 0; k < level.size(); ++k) {
      const LodMesh& m = level[k];
      ASSERT_EQ(m.source.size(), m.positions.size());
      ASSERT_EQ(m.triangle_source.size() * 3, m.indices.size());
      for (uint32_t v : m.source)
        ASSERT_LT(v, s.meshes[k].positions.size());
      for (uint32_t i : m.indices)
        ASSERT_LT(i, m.positions.size());
      for (uint32_t t : m.triangle_source)
        ASSERT_LT(t, s.meshes[k].triangle_count());
    }
  }
}

TEST(PlantLod, KeptLeavesAreNestedAndEnlargedAboutTheirCentres) {
  const Scene& s = tree();
  const PlantLod lod = make_plant_lod(s);
  size_t k = 0;  // the leaves mesh
  while (k < s.meshes.size() && s.meshes[k].roles[0] != Role::Foliage)
    ++k;
  ASSERT_LT(k, s.meshes.size());
  const Mesh& leaves = s.meshes[k];
  std::set<uint32_t> previous;
  for (int l = 0; l < kLodLevels; ++l) {
    const LodMesh& m = lod.levels[size_t(l)][k];
    const std::set<uint32_t> kept = kept_leaves(m, leaves);
    for (uint32_t id : kept)
      EXPECT_TRUE(l == 0 || previous.count(id)) << "leaf " << id << " at level " << l + 1;
    previous = kept;
    // A kept leaf is enlarged sqrt(2)^(l+1) about its centre: its edges grow as much.
    const float scale = std::pow(std::sqrt(2.0f), float(l + 1));
    ASSERT_GE(m.indices.size(), 3u);
    ASSERT_EQ(leaves.roles[m.triangle_source[0]], Role::Foliage);
    const uint32_t i0 = m.indices[0], i1 = m.indices[1];
    const float edge = glm::length(leaves.positions[m.source[i0]] - leaves.positions[m.source[i1]]);
    EXPECT_NEAR(glm::length(m.positions[i0] - m.positions[i1]), scale * edge, 1e-4f * scale);
  }
  EXPECT_LT(previous.size(), 1200u / 32u);
  EXPECT_GT(previous.size(), 0u);
}

TEST(PlantLod, DeterministicAndCachedPerPlant) {
  Scene park;
  park.meshes = tree().meshes;
  park.materials = tree().materials;
  Plant plant{"tree", {}, tree().hierarchy};
  for (size_t m = 0; m < park.meshes.size(); ++m)
    plant.meshes.push_back(uint32_t(m));
  park.plants = {plant};
  park.instances = {{0, glm::mat4(1.0f), "a"},
                    {0, glm::translate(glm::mat4(1.0f), glm::vec3(9, 0, 0)), "b"}};
  const ResultCache cache(temp_dir("lod-cache"));
  const std::vector<PlantLod> first = scene_lods(park, &cache);
  ASSERT_EQ(first.size(), 1u);
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(cache.dir()))
    files += e.path().filename().string().rfind("lod-", 0) == 0;
  EXPECT_EQ(files, 1u);
  const std::vector<PlantLod> again = scene_lods(park, &cache);
  const PlantLod fresh = make_plant_lod(plant_scene(park, 0, false));
  for (int l = 0; l < kLodLevels; ++l)
    for (size_t k = 0; k < park.meshes.size(); ++k) {
      EXPECT_EQ(again[0].levels[size_t(l)][k].positions, fresh.levels[size_t(l)][k].positions);
      EXPECT_EQ(again[0].levels[size_t(l)][k].indices, fresh.levels[size_t(l)][k].indices);
      EXPECT_EQ(first[0].levels[size_t(l)][k].source, fresh.levels[size_t(l)][k].source);
    }
  // A damaged entry is recomputed.
  for (const auto& e : std::filesystem::directory_iterator(cache.dir()))
    write_file(e.path().string(), "garbage");
  const std::vector<PlantLod> repaired = scene_lods(park, &cache);
  EXPECT_EQ(repaired[0].levels[2][0].indices, fresh.levels[2][0].indices);
  // A flat scene has no levels.
  EXPECT_TRUE(scene_lods(tree(), &cache).empty());
}

}  // namespace
}  // namespace sylva::test
