// Instanced draws (core/gl/instance_draws.h) against the same scene flattened into world-space
// meshes (core/scene/instances.h): every target agrees, ids included, with mirrored, scaled,
// turned and out-of-view instances.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>
#include <optional>

#include "core/gl/instance_draws.h"
#include "core/gl/rasterizer.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "tests/core/gl/raster_scenes.h"

namespace sylva {
namespace {

using namespace sylva::test;

// A plant of two meshes: a crown of spheres (foliage, 3 leaves) and a trunk quad (wood).
Scene plant_scene(bool with_ground) {
  Mesh crown;
  crown.name = "crown";
  for (int i = 0; i < 3; ++i)
    add_sphere(crown, glm::vec3(0.4f * float(i - 1), 1.2f + 0.2f * float(i % 2), 0.0f), 0.35f, 24,
               12);
  Mesh trunk = make_quad(0.08f, 0.0f);
  trunk.name = "trunk";
  for (glm::vec3& p : trunk.positions)
    p.y = (p.y + 0.08f) * 6.0f;
  Scene s = scene_of({crown, trunk});
  s.meshes[0].roles.assign(s.meshes[0].triangle_count(), Role::Foliage);
  s.meshes[1].roles.assign(s.meshes[1].triangle_count(), Role::Wood);
  s.plants.push_back({"tree", {0, 1}, {}});
  const glm::mat4 id(1.0f);
  s.instances = {
      {0, id, "a"},
      {0, glm::rotate(glm::translate(id, glm::vec3(1.5f, 0, -0.5f)), 0.7f, glm::vec3(0, 1, 0)),
       "b"},
      {0, glm::scale(glm::translate(id, glm::vec3(-1.4f, 0, 0.3f)), glm::vec3(1.3f, 0.8f, 1.1f)),
       "c"},
      {0, glm::scale(glm::translate(id, glm::vec3(0.2f, 0, 1.2f)), glm::vec3(-1.0f, 1.0f, 1.0f)),
       "mirrored"},
  };
  if (with_ground) {
    Mesh g = make_quad(3.0f, 0.0f);
    g.name = "ground";
    g.material = 0;
    for (glm::vec3& p : g.positions)
      p = glm::vec3(p.x, -0.01f, p.y);
    g.normals.assign(4, glm::vec3(0, 1, 0));
    g.indices = {0, 2, 1, 0, 3, 2};  // facing +Y
    g.roles.assign(g.triangle_count(), Role::Ground);
    s.meshes.push_back(g);
    s.plants.push_back({"rest", {2}, {}});
    s.instances.insert(s.instances.begin(), {1, id, ""});
  }
  LoadOptions keep;
  finish_scene(s, keep, true);
  // Clusters as leaf_clusters makes them: a leaf each, the wood one more.
  for (Mesh& m : s.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      m.cluster_ids[t] = m.roles[t] == Role::Foliage ? m.primitive_ids[t] : 4u;
  return s;
}

GBuffer render(const Scene& s, const Camera& cam, IdKind ids, size_t* drawn = nullptr) {
  Rasterizer r(gl());
  r.upload(s);
  RasterRequest q = request_of(Target::Color | Target::Normal | Target::Depth | Target::Id, ids);
  const GBuffer g = r.render(cam, Lighting::three_point(), q);
  if (drawn) *drawn = r.last_drawn_instances();
  return g;
}

// The share of pixels where `a` and `b` differ by more than `tolerance` in any channel.
double differing(const cv::Mat& a, const cv::Mat& b, double tolerance) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  d.reshape(1, int(d.total())).convertTo(d, CV_64F);
  cv::Mat worst;
  cv::reduce(d, worst, 1, cv::REDUCE_MAX);
  return double(cv::countNonZero(worst > tolerance)) / double(d.total());
}

TEST(InstancedRaster, MatchesTheFlattenedScene) {
  for (bool ground : {false, true}) {
    const Scene s = plant_scene(ground);
    const Scene flat = flatten(s);
    const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 240, 200);
    EXPECT_EQ(s.framing_sphere().radius, flat.framing_sphere().radius);
    for (IdKind kind : {IdKind::Primitive, IdKind::Cluster, IdKind::Object, IdKind::Material}) {
      size_t drawn = 0;
      const GBuffer a = render(s, cam, kind, &drawn);
      const GBuffer b = render(flat, cam, kind);
      EXPECT_EQ(drawn, s.instances.size());
      EXPECT_LT(differing(a.color, b.color, 2), 0.002) << "ground " << ground;
      EXPECT_LT(differing(a.normal, b.normal, 1e-3), 0.002);
      EXPECT_LT(differing(a.depth, b.depth, 1e-4), 0.002);
      EXPECT_LT(differing(a.id, b.id, 0), 0.002) << "id kind " << int(kind);
      EXPECT_GT(id_set(a.id).size(), kind == IdKind::Material ? 1u : 5u);
    }
  }
}

TEST(InstancedRaster, ClusterIdsAreThoseOfTheLayout) {
  const Scene s = plant_scene(false);
  const IdLayout l = id_layout(s);
  const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 200, 200);
  const std::set<int32_t> ids = id_set(render(s, cam, IdKind::Cluster).id);
  // Three leaves per instance, four instances; the wood of all of them one cluster.
  EXPECT_EQ(l.branch_cluster, 13u);
  EXPECT_TRUE(ids.count(13));
  EXPECT_TRUE(ids.count(12));  // the last instance's third leaf
  EXPECT_EQ(*ids.rbegin(), 13);
}

TEST(InstancedRaster, InstancesOutOfViewAreNotDrawnAndChangeNothing) {
  Scene s = plant_scene(false);
  const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 160, 160);
  const GBuffer before = render(s, cam, IdKind::Object);
  // Behind the camera and far to the side: outside the view volume.
  const glm::vec3 behind = cam.eye + 3.0f * (cam.eye - s.framing_sphere().centre);
  s.instances.push_back({0, glm::translate(glm::mat4(1.0f), behind), "behind"});
  s.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(500, 0, 0)), "far"});
  size_t drawn = 0;
  const GBuffer after = render(s, cam, IdKind::Object, &drawn);
  EXPECT_EQ(drawn, 4u);
  EXPECT_EQ(differing(before.color, after.color, 0), 0.0);
  EXPECT_EQ(differing(before.id, after.id, 0), 0.0);
}

// The draws of a forest in pieces and with waits between them (a CPU renderer's limits), in
// one piece per batch (a GPU's), or in tiny pieces: the same triangles in the same order.
TEST(InstancedRaster, DrawLimitsChangeNoPixel) {
  const Scene s = plant_scene(true);
  const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 160, 160);
  const RasterRequest q = request_of(Target::Color | Target::Depth | Target::Id, IdKind::Cluster);
  const auto draw = [&](std::optional<DrawLimits> limits) {
    Rasterizer r(gl());
    if (limits) r.set_draw_limits(*limits);
    r.upload(s);
    return r.render(cam, Lighting::three_point(), q);
  };
  const GBuffer cpu = draw(std::nullopt);
  for (const DrawLimits& limits : {DrawLimits{}, DrawLimits{100, 300}, DrawLimits{7, 20}}) {
    const GBuffer other = draw(limits);
    EXPECT_EQ(differing(cpu.color, other.color, 0), 0.0) << limits.chunk_triangles;
    EXPECT_EQ(differing(cpu.depth, other.depth, 0), 0.0) << limits.chunk_triangles;
    EXPECT_EQ(differing(cpu.id, other.id, 0), 0.0) << limits.chunk_triangles;
  }
}

// Every level of `s`'s one plant: the crown's first sphere (its first third of triangles) and
// the whole trunk, as vertex and triangle sources.
std::vector<PlantLod> first_sphere_levels(const Scene& s) {
  PlantLod lod;
  for (int l = 0; l < kLodLevels; ++l) {
    std::vector<LodMesh> level;
    for (uint32_t mi : s.plants[0].meshes) {
      const Mesh& m = s.meshes[mi];
      LodMesh out;
      out.positions = m.positions;
      for (uint32_t v = 0; v < m.positions.size(); ++v)
        out.source.push_back(v);
      const size_t keep = m.roles[0] == Role::Foliage ? m.triangle_count() / 3 : m.triangle_count();
      for (uint32_t t = 0; t < keep; ++t) {
        out.triangle_source.push_back(t);
        out.indices.insert(out.indices.end(), m.indices.begin() + 3 * t,
                           m.indices.begin() + 3 * t + 3);
      }
      level.push_back(out);
    }
    lod.levels.push_back(level);
  }
  return {lod};
}

GBuffer render_lod(const Scene& s, const Camera& cam, bool lod) {
  Rasterizer r(gl());
  r.upload(s);
  if (lod) r.set_lod(s, first_sphere_levels(s));
  return r.render(cam, Lighting::three_point(), request_of(Target::Color | Target::Id));
}

TEST(InstancedRaster, LevelsOfDetailFollowTheProjectedSize) {
  const Scene s = plant_scene(false);
  // Large on screen (about 1,700 triangles over thousands of pixels each): drawn whole.
  const Camera near = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 240, 240);
  EXPECT_EQ(differing(render_lod(s, near, true).color, render_lod(s, near, false).color, 0), 0.0);
  // A few dozen pixels across: drawn at a coarser level, as the scene with only those
  // triangles is.
  const Camera far = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 40, 40);
  const GBuffer coarse = render_lod(s, far, true);
  EXPECT_GT(differing(coarse.color, render_lod(s, far, false).color, 0), 0.0);
  Scene reduced = s;
  const PlantLod lod = first_sphere_levels(s)[0];
  for (size_t k = 0; k < s.plants[0].meshes.size(); ++k) {
    Mesh& m = reduced.meshes[s.plants[0].meshes[k]];
    m = lod_as_mesh(m, lod.levels[0][k]);
  }
  EXPECT_EQ(differing(coarse.color, render_lod(reduced, far, false).color, 0), 0.0);
  EXPECT_EQ(differing(coarse.id, render_lod(reduced, far, false).id, 0), 0.0);
}

TEST(InstancedRaster, TheVisibleSphereHoldsTheInstancesInViewOnly) {
  Scene s = plant_scene(true);  // with a ground plant, which is left out
  const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 160, 160);
  const Sphere all = visible_instances_sphere(s, cam);
  ASSERT_FALSE(all.empty());
  EXPECT_LT(all.radius, 3.0f);  // not the 6-unit ground
  s.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(500, 0, 0)), "far"});
  const Sphere seen = visible_instances_sphere(s, cam);
  EXPECT_EQ(seen.centre, all.centre);
  EXPECT_EQ(seen.radius, all.radius);
  EXPECT_TRUE(visible_instances_sphere(flatten(s), cam).empty());  // a flat scene: none
}

// One ellipsoidal shell around the crown (plant space) as the raster pass takes it.
AoShading::PlantShells crown_shell() {
  AoShading::PlantShells p;
  p.alpha_rho = 3.0f;
  const glm::mat3 l(glm::vec3(0.9f, 0.0f, 0.0f), glm::vec3(0.0f, 0.5f, 0.0f),
                    glm::vec3(0.0f, 0.0f, 0.45f));  // axes * radii
  p.centres = {glm::vec3(0.0f, 1.25f, 0.0f)};
  p.anchors = p.centres;
  p.inverse = {glm::inverse(l)};
  p.transpose = {glm::transpose(l)};
  p.volume_scale = {std::abs(glm::determinant(l))};
  return p;
}

GBuffer render_ao(const Scene& s, const Camera& cam, const AoShading& ao) {
  Rasterizer r(gl());
  r.upload(s);
  RasterRequest q = request_of(Target::Ao);
  q.ao = ao;
  return r.render(cam, Lighting::three_point(), q);
}

TEST(InstancedRaster, EachInstanceDarkensItsLeavesAsItsPlantAlone) {
  // One instance turned and moved, against the same plant flattened with its shell moved
  // alike into world space (the uniform path of a flat scene).
  Scene s = plant_scene(false);
  const glm::mat4 t =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 1)), 0.8f, glm::vec3(0, 1, 0));
  s.instances = {{0, t, "one"}};
  const Scene flat = flatten(s);
  const AoShading::PlantShells shell = crown_shell();
  AoShading instanced;
  instanced.model = AoShading::Model::Shells;
  instanced.plant_shells = {shell};
  instanced.crowns = {glm::vec4(0.0f)};
  AoShading world;
  world.model = AoShading::Model::Shells;
  world.alpha_rho = shell.alpha_rho;
  const glm::mat3 r(t);
  world.centres = {glm::vec3(t * glm::vec4(shell.centres[0], 1.0f))};
  world.anchors = world.centres;
  world.inverse = {shell.inverse[0] * glm::transpose(r)};
  world.transpose = {shell.transpose[0] * glm::transpose(r)};
  world.volume_scale = shell.volume_scale;
  const Camera cam = make_orbit_camera(s.framing_sphere(), OrbitParams{}, 160, 160);
  const GBuffer a = render_ao(s, cam, instanced), b = render_ao(flat, cam, world);
  EXPECT_LT(differing(a.ao, b.ao, 2e-3), 0.002);
  double mean = cv::mean(a.ao, a.ao > 0)[0];
  EXPECT_LT(mean, 0.95);  // the shell darkens the leaves
}

TEST(InstancedRaster, NeighbouringCrownsAddTheirOcclusion) {
  // Wood and ground near two crowns are darker than near one; far from both, as without any.
  Scene s = plant_scene(true);
  AoShading ao;
  ao.model = AoShading::Model::Shells;
  ao.plant_shells = {crown_shell(), {}};  // the tree, the ground
  for (const Instance& inst : s.instances)
    ao.crowns.push_back(inst.plant == 0
                            ? glm::vec4(glm::vec3(inst.transform * glm::vec4(0, 1.25f, 0, 1)), 0.6f)
                            : glm::vec4(0.0f));
  OrbitParams top;
  top.elevation_deg = 89.0f;
  const Camera cam = make_orbit_camera(s.framing_sphere(), top, 200, 200);
  const GBuffer both = render_ao(s, cam, ao);
  AoShading one = ao;
  for (size_t i = 2; i < one.crowns.size(); ++i)
    one.crowns[i] = glm::vec4(0.0f);  // only the ground's (none) and the first tree's
  const GBuffer single = render_ao(s, cam, one);
  EXPECT_LT(cv::sum(both.ao)[0], cv::sum(single.ao)[0] - 1.0);
  cv::Mat darker = both.ao < single.ao - 1e-4f;
  EXPECT_GT(cv::countNonZero(darker), 200);
  EXPECT_EQ(cv::countNonZero(both.ao > single.ao + 1e-4f), 0);
}

}  // namespace
}  // namespace sylva
