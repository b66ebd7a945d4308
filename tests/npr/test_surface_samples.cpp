// Surface samples (npr/surface_samples.h): every triangle but the ground is cut into k x k
// sub-triangles whose centroids carry their area, so the areas add up to the surface's; alpha-
// cutout texels are left out; the spacing follows the plant's size; the same scene gives the
// same points; the render-graph node makes them once per memo.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "core/graph/render_graph.h"
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
    const int out = add_surface_samples_pass(g, &scene, memo);
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

}  // namespace
}  // namespace sylva::test
