// Surface samples (npr/surface_samples.h): every triangle but the ground is cut into k x k
// sub-triangles whose centroids carry their area, so the areas add up to the surface's; alpha-
// cutout texels are left out; the spacing follows the plant's size; the same scene gives the
// same points; the render-graph node makes them once per memo.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <tuple>

#include "core/graph/render_graph.h"
#include "core/scene/instances.h"
#include "npr/surface_samples.h"

namespace sylva::test {
namespace {

// A unit square in the z = 0 plane (two triangles), cluster 3, uvs over [0, 1]², and a
// 10 x 10 ground quad at y = -1 when `ground`.
Scene square_scene(bool ground = false) {
  Scene s;
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.roles = {Role::Foliage, Role::Foliage};
  m.cluster_ids = {3, 3};
  m.primitive_ids = {1, 1};
  s.meshes.push_back(m);
  if (ground) {
    Mesh g;
    g.positions = {{-5, -1, -5}, {5, -1, -5}, {5, -1, 5}, {-5, -1, 5}};
    g.indices = {0, 2, 1, 0, 3, 2};
    g.roles = {Role::Ground, Role::Ground};
    g.cluster_ids = {1, 1};
    g.primitive_ids = {2, 2};
    s.meshes.push_back(g);
  }
  return s;
}

double total_area(const SurfaceSamples& s) {
  return std::accumulate(s.areas.begin(), s.areas.end(), 0.0);
}

TEST(SurfaceSamples, AreasAddUpToTheSurfaceAndPointsLieOnIt) {
  const Scene scene = square_scene();
  for (float spacing : {2.0f, 0.3f, 0.05f}) {
    const SurfaceSamples s = sample_surfaces(scene, spacing);
    ASSERT_GT(s.size(), 0u);
    EXPECT_NEAR(total_area(s), 1.0, 1e-5) << spacing;
    for (size_t i = 0; i < s.size(); ++i) {
      EXPECT_FLOAT_EQ(s.positions[i].z, 0.0f);
      EXPECT_GE(s.positions[i].x, 0.0f);
      EXPECT_LE(s.positions[i].x, 1.0f);
      EXPECT_NEAR(std::abs(s.normals[i].z), 1.0f, 1e-6f);
      EXPECT_EQ(s.clusters[i], 3u);
    }
  }
  // Finer spacing, more points: k = ceil(sqrt(0.5) / spacing) per side, k² per triangle.
  EXPECT_EQ(sample_surfaces(scene, 2.0f).size(), 2u);
  EXPECT_EQ(sample_surfaces(scene, 0.3f).size(), 2u * 9u);
  // At most 16 x 16 per triangle however fine the spacing.
  EXPECT_EQ(sample_surfaces(scene, 1e-4f).size(), 2u * 256u);
}

TEST(SurfaceSamples, TheGroundIsLeftOutAndSetsNoSpacing) {
  const Scene with = square_scene(true), without = square_scene(false);
  EXPECT_EQ(sample_surfaces(with, 0.3f).size(), sample_surfaces(without, 0.3f).size());
  EXPECT_FLOAT_EQ(coverage_spacing(with), coverage_spacing(without));
  EXPECT_NEAR(coverage_spacing(without), std::sqrt(2.0f) / 400.0f, 1e-7f);
  EXPECT_EQ(coverage_spacing(Scene{}), 0.0f);
}

TEST(SurfaceSamples, AlphaCutoutTexelsAreLeftOut) {
  Scene s = square_scene();
  // Left half of the texture transparent: the samples keep the right half's area.
  Texture t;
  t.width = 2;
  t.height = 1;
  t.rgba = {255, 255, 255, 0, 255, 255, 255, 255};
  s.textures.push_back(t);
  Material m;
  m.alpha_mode = AlphaMode::Mask;
  m.alpha_cutoff = 0.5f;
  m.base_color_texture = 0;
  s.materials.push_back(m);
  s.meshes[0].material = 0;
  const SurfaceSamples cut = sample_surfaces(s, 0.02f);
  EXPECT_NEAR(total_area(cut), 0.5, 0.02);
  for (const glm::vec3& p : cut.positions)
    EXPECT_GE(p.x, 0.45f);
  // Opaque, the same material keeps everything.
  s.materials[0].alpha_mode = AlphaMode::Opaque;
  EXPECT_NEAR(total_area(sample_surfaces(s, 0.02f)), 1.0, 1e-5);
}

TEST(SurfaceSamples, SameSceneSamePoints) {
  const Scene scene = square_scene();
  const SurfaceSamples a = sample_surfaces(scene, 0.1f), b = sample_surfaces(scene, 0.1f);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a.positions[i], b.positions[i]);
    EXPECT_EQ(a.areas[i], b.areas[i]);
  }
}

TEST(SurfaceSamples, TheNodeMakesThemOncePerMemo) {
  const Scene scene = square_scene();
  auto memo = std::make_shared<SurfaceSampleMemo>();
  std::shared_ptr<const SurfaceSamples> first;
  for (int run = 0; run < 2; ++run) {
    RenderGraph g;
    const SamplesHandle out = add_surface_samples_pass(g, &scene, memo);
    g.present(out);
    g.compile();
    g.execute();
    const auto samples = g.get<std::shared_ptr<const SurfaceSamples>>(out);
    ASSERT_TRUE(samples);
    EXPECT_NEAR(total_area(*samples), 1.0, 1e-5);
    if (run == 0) first = samples;
    EXPECT_EQ(samples.get(), first.get());  // the memo's, not made again
  }
}

// A plant of the unit square (foliage, cluster 3) and a wood triangle (cluster 1), placed by
// `transforms`.
Scene instanced_square(const std::vector<glm::mat4>& transforms) {
  Scene s = square_scene();
  Mesh wood;
  wood.positions = {{0, -1, 0}, {0.2f, -1, 0}, {0.1f, 0, 0}};
  wood.indices = {0, 1, 2};
  wood.roles = {Role::Wood};
  wood.cluster_ids = {1};
  wood.primitive_ids = {2};
  s.meshes.push_back(wood);
  s.plants.push_back({"square", {0, 1}, {}});
  for (const glm::mat4& t : transforms)
    s.instances.push_back({0, t, ""});
  validate_instances(s, "test");
  return s;
}

// The samples in an order that does not depend on the triangles' winding (the flattened scene
// reverses a mirrored instance's, which visits a triangle's sub-triangles in another order).
std::vector<size_t> by_place(const SurfaceSamples& s) {
  std::vector<size_t> order(s.size());
  std::iota(order.begin(), order.end(), size_t(0));
  auto key = [&s](size_t i) {
    const glm::vec3 p = glm::round(s.positions[i] * 1e4f);
    return std::tuple(s.clusters[i], p.x, p.y, p.z);
  };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  return order;
}

// Same-scale instances (turned, moved, mirrored) give the points of the flattened scene, with
// the id buffer's clusters (each instance's own, the wood's shared).
TEST(SurfaceSamples, InstancesGiveThePointsOfTheFlattenedScene) {
  const glm::mat4 two = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
  const Scene scene = instanced_square(
      {two, glm::rotate(glm::translate(two, glm::vec3(3, 0, 1)), 0.7f, glm::vec3(0, 1, 0)),
       glm::scale(glm::translate(two, glm::vec3(-3, 0, 0)), glm::vec3(-1, 1, 1))});
  const Scene flat = flatten(scene);
  EXPECT_FLOAT_EQ(coverage_spacing(scene), coverage_spacing(flat));
  const float spacing = 0.3f;
  const SurfaceSamples a = sample_surfaces(scene, spacing), b = sample_surfaces(flat, spacing);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.size(), 3u * (2u * 25u + 9u));  // k = 5 on the square's halves, 3 on the wood
  const std::vector<size_t> ia = by_place(a), ib = by_place(b);
  std::map<uint32_t, int> clusters;
  for (size_t k = 0; k < a.size(); ++k) {
    const size_t i = ia[k], j = ib[k];
    EXPECT_LT(glm::length(a.positions[i] - b.positions[j]), 1e-5f) << k;
    EXPECT_LT(1.0f - std::abs(glm::dot(a.normals[i], b.normals[j])), 1e-5f) << k;
    EXPECT_NEAR(a.areas[i], b.areas[j], 1e-5f * b.areas[j]) << k;
    EXPECT_EQ(a.clusters[i], b.clusters[j]) << k;
    ++clusters[a.clusters[i]];
  }
  EXPECT_EQ(clusters.size(), 4u);  // three instances' leaves, one wood
}

// Instances of other scales keep every instance's area; past 2^22 points the instances are
// thinned evenly, the areas raised to keep the total, the same way on every run.
TEST(SurfaceSamples, InstancesKeepTheirAreasAndAreThinnedPastTheBudget) {
  const Scene scaled =
      instanced_square({glm::mat4(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(3.0f, 1.0f, 2.0f))});
  EXPECT_NEAR(total_area(sample_surfaces(scaled, 0.05f)),
              total_area(sample_surfaces(flatten(scaled), 0.05f)), 1e-4);
  std::vector<glm::mat4> many;
  for (int i = 0; i < 9000; ++i)
    many.push_back(
        glm::translate(glm::mat4(1.0f), glm::vec3(float(i % 100) * 2, float(i / 100) * 3, 0)));
  const Scene park = instanced_square(many);
  const SurfaceSamples a = sample_surfaces(park, 1e-3f);  // 2 x 256 + 256 points per instance
  EXPECT_LE(a.size(), size_t(1) << 22);
  EXPECT_GT(a.size(), size_t(0.99 * double(size_t(1) << 22)));
  EXPECT_NEAR(total_area(a), 9000 * 1.1, 9000 * 1.1 * 0.005);
  const SurfaceSamples b = sample_surfaces(park, 1e-3f);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.positions.back(), b.positions.back());
}

}  // namespace
}  // namespace sylva::test
