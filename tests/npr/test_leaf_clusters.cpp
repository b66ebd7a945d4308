// Leaf clusters: Dudley's hierarchy rule on a hand-made branch tree, k-means on leaf
// centroids (determinism, k at and beyond its range), non-foliage in the last cluster.
#include <gtest/gtest.h>

#include <set>

#include "core/error.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "npr/leaf_clusters.h"
#include "samples/plants.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

// A mesh of disjoint small quads (leaves) centred at the given points.
Mesh leaves_at(const std::vector<glm::vec3>& centres) {
  Mesh m;
  m.name = "leaves";
  for (const glm::vec3& c : centres) {
    const uint32_t b = uint32_t(m.positions.size());
    for (glm::vec3 d : {glm::vec3(-.1f, -.1f, 0), glm::vec3(.1f, -.1f, 0), glm::vec3(.1f, .1f, 0),
                        glm::vec3(-.1f, .1f, 0)})
      m.positions.push_back(c + d);
    m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
  return m;
}

Mesh trunk() {
  Mesh m;
  m.name = "trunk";
  m.positions = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}};
  m.indices = {0, 1, 2};
  return m;
}

// Cluster id of each leaf (first triangle of each quad of mesh 1).
std::vector<uint32_t> leaf_clusters(const Scene& s) {
  std::vector<uint32_t> out;
  for (size_t t = 0; t < s.meshes[1].triangle_count(); t += 2)
    out.push_back(s.meshes[1].cluster_ids[t]);
  return out;
}

Scene plant() {
  Scene s;
  s.meshes = {trunk(), leaves_at({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}})};
  s.hierarchy.branch_parent = {-1, 0, 1, 1, 0};
  s.hierarchy.branch_diameter = {1.0f, 0.5f, 0.1f, 0.1f, 0.08f};
  s.hierarchy.leaf_branch = {2, 3, 2, 4, 0};
  finish_scene(s, {});  // "trunk" is wood, "leaves" foliage by name
  return s;
}

TEST(Clusters, HierarchyDivisionDiameter) {
  Scene s = plant();
  ClusterOptions o;
  o.division_diameter = 0.3f;
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 2, 1, 3, 4}));
  EXPECT_EQ(s.meshes[0].cluster_ids[0], 5u);  // wood: K + 1
  EXPECT_NE(s.report.cluster_method.find("hierarchy"), std::string::npos);
  o.division_diameter = 0.6f;  // branch 1 is now thin enough to gather leaves 0-2
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 1, 1, 2, 3}));
  EXPECT_EQ(s.meshes[0].cluster_ids[0], 4u);
  o.division_diameter = 0.0f;  // auto: the diameter whose count is closest to --clusters
  o.clusters = 4;              // the thinnest division already gives 4 (each branch alone)
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 2, 1, 3, 4}));
  o.clusters = 3;  // division 1.0: branch 1 gathers leaves 0-2; leaf 4 sits on the trunk
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 1, 1, 2, 3}));
  EXPECT_NE(s.report.cluster_method.find("division diameter 1)"), std::string::npos)
      << s.report.cluster_method;
  o.clusters = 1;
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 1, 1, 1, 1}));
  o.clusters = 0;
  o.division_diameter = 10.0f;  // everything below the trunk's root: one cluster
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), (std::vector<uint32_t>{1, 1, 1, 1, 1}));
}

TEST(Clusters, HierarchyMismatchFallsBackToKMeans) {
  Scene s = plant();
  s.hierarchy.leaf_branch.pop_back();
  assign_clusters(s, {});
  EXPECT_NE(s.report.cluster_method.find("k-means"), std::string::npos);
  EXPECT_FALSE(s.report.warnings.empty());
  ClusterOptions o;
  o.use_hierarchy = false;
  Scene t = plant();
  assign_clusters(t, o);
  EXPECT_NE(t.report.cluster_method.find("k-means"), std::string::npos);
}

Scene three_groups() {
  std::vector<glm::vec3> c;
  for (int g = 0; g < 3; ++g)
    for (int i = 0; i < 10; ++i)
      c.push_back(glm::vec3(100.0f * g, 0.3f * float(i % 3), 0.3f * float(i / 3)));
  Scene s;
  s.meshes = {trunk(), leaves_at(c)};
  finish_scene(s, {});
  return s;
}

TEST(Clusters, KMeansSeparatesGroupsDeterministically) {
  Scene s = three_groups();
  ClusterOptions o;
  o.clusters = 3;
  o.seed = 7;
  assign_clusters(s, o);
  const std::vector<uint32_t> first = leaf_clusters(s);
  for (int i = 0; i < 30; ++i)
    EXPECT_EQ(first[size_t(i)], uint32_t(i / 10 + 1)) << i;
  EXPECT_EQ(s.meshes[0].cluster_ids[0], 4u);
  EXPECT_EQ(s.report.cluster_method, "k-means (k=3, seed 7)");
  Scene t = three_groups();
  assign_clusters(t, o);
  EXPECT_EQ(leaf_clusters(t), first);
  // A different seed may pick other centres but the first leaf is always cluster 1.
  o.seed = 0;
  assign_clusters(t, o);
  EXPECT_EQ(leaf_clusters(t)[0], 1u);
}

// Beyond 20,000 leaves the centres come from a strided sample; labels stay right and stable.
TEST(Clusters, KMeansOnManyLeaves) {
  std::vector<glm::vec3> c;
  for (int i = 0; i < 45000; ++i)
    c.push_back(
        glm::vec3(100.0f * float(i % 3), 0.01f * float(i / 3 % 100), 0.01f * float(i / 300)));
  Scene s;
  s.meshes = {trunk(), leaves_at(c)};
  finish_scene(s, {});
  ClusterOptions o;
  o.clusters = 3;
  assign_clusters(s, o);
  const std::vector<uint32_t> ids = leaf_clusters(s);
  for (size_t i = 0; i < ids.size(); ++i)
    ASSERT_EQ(ids[i], uint32_t(i % 3 + 1)) << i;
  assign_clusters(s, o);
  EXPECT_EQ(leaf_clusters(s), ids);
}

TEST(Clusters, KAtTheEndsOfItsRange) {
  Scene s = three_groups();
  ClusterOptions o;
  o.clusters = 0;  // auto: round(sqrt(30 / 2)) = 4
  assign_clusters(s, o);
  EXPECT_EQ(s.report.cluster_method.find("k-means (k=4"), 0u);
  o.clusters = 1;
  assign_clusters(s, o);
  EXPECT_EQ(
      std::set<uint32_t>(s.meshes[1].cluster_ids.begin(), s.meshes[1].cluster_ids.end()).size(),
      1u);
  EXPECT_EQ(s.meshes[0].cluster_ids[0], 2u);
  for (int k : {30, 4096}) {  // k clamps to the leaf count: every leaf its own cluster
    o.clusters = k;
    assign_clusters(s, o);
    const std::vector<uint32_t> ids = leaf_clusters(s);
    for (size_t i = 0; i < ids.size(); ++i)
      EXPECT_EQ(ids[i], uint32_t(i + 1));
    EXPECT_EQ(s.meshes[0].cluster_ids[0], 31u);
  }
  for (int k : {4097, -1}) {
    o.clusters = k;
    try {
      assign_clusters(s, o);
      FAIL() << "k = " << k << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "--clusters");
    }
  }
  o.clusters = 3;
  o.division_diameter = -1.0f;
  EXPECT_THROW(assign_clusters(s, o), InputError);
}

// A sample plant keeps its hierarchy through write_glb and load_scene, and the hierarchy
// rule applies to it after the round trip exactly as before.
TEST(Clusters, SamplePlantHierarchySurvivesGlb) {
  PlantOptions po;
  po.kind = PlantKind::Bush;
  po.leaves = 400;
  Scene plant = make_plant(po);
  const std::string path = test::temp_dir("plant") + "/bush.glb";
  write_glb(plant, path);
  Scene loaded = load_scene(path);
  EXPECT_EQ(loaded.report.foliage_rule, "sylva_role extras");
  assign_clusters(plant, {});
  assign_clusters(loaded, {});
  EXPECT_EQ(loaded.report.cluster_method.find("hierarchy"), 0u) << loaded.report.cluster_method;
  EXPECT_EQ(loaded.report.cluster_method, plant.report.cluster_method);
  ASSERT_EQ(loaded.meshes.size(), plant.meshes.size());
  for (size_t m = 0; m < plant.meshes.size(); ++m) {
    EXPECT_EQ(loaded.meshes[m].primitive_ids, plant.meshes[m].primitive_ids);
    EXPECT_EQ(loaded.meshes[m].cluster_ids, plant.meshes[m].cluster_ids);
  }
  EXPECT_GT(loaded.max_cluster_id(), 2u);
}

// The automatic division diameter of a real sample lands near the default count
// (sqrt(leaves / 2), capped at 64), not at one cluster per twig.
TEST(Clusters, SampleTreeAutoCountIsNearTheDefault) {
  for (PlantKind kind : {PlantKind::Tree, PlantKind::Bush, PlantKind::Conifer}) {
    PlantOptions po;
    po.kind = kind;
    po.leaves = 4000;  // default count: lround(sqrt(2000)) = 45
    Scene plant = make_plant(po);
    assign_clusters(plant, {});
    const uint32_t k = plant.max_cluster_id() - 1;  // minus the non-foliage cluster
    EXPECT_GE(k, 20u) << plant.report.cluster_method;
    EXPECT_LE(k, 90u) << plant.report.cluster_method;
  }
}

TEST(Clusters, NoFoliage) {
  Scene s;
  s.meshes = {trunk()};
  finish_scene(s, {"none"});
  assign_clusters(s, {});
  EXPECT_EQ(s.meshes[0].cluster_ids[0], 1u);
  EXPECT_EQ(s.max_cluster_id(), 1u);
}

}  // namespace
}  // namespace sylva
