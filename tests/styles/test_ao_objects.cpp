// Hegeman et al.'s object interaction and grass in the raster pass (core/gl/shaders.cpp via
// npr/ao_pass.h): with ao.model = hegeman-*, fragments that are not foliage (the --ground
// plane, the trunk) get Eq. 7-8 of the crown's sphere, grass blades Eq. 9 times that; both
// checked per pixel against npr/hegeman_ao.h's object_visibility and grass_visibility, plus
// the picture they should make: darker under the crown than far from it, grass darker at the
// roots than at the tips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <string>

#include "core/error.h"
#include "core/gl/depth_range.h"
#include "core/gl/raster_pass.h"
#include "core/scene/ground_plane.h"
#include "npr/ao_pass.h"
#include "npr/hegeman_ao.h"
#include "samples/grass.h"
#include "samples/plants.h"

namespace sylva {
namespace {

constexpr int kSize = 96;

Scene small_tree() {
  PlantOptions po;
  po.kind = PlantKind::Tree;
  po.leaves = 2000;
  po.seed = 3;
  return make_plant(po);
}

// Appends `part`'s meshes and materials to `scene`, xz scaled by `spread` (y unchanged).
void merge(Scene& scene, Scene part, float spread) {
  const int offset = int(scene.materials.size());
  scene.materials.insert(scene.materials.end(), part.materials.begin(), part.materials.end());
  const uint32_t ids = scene.max_primitive_id();
  for (Mesh& m : part.meshes) {
    if (m.material >= 0) m.material += offset;
    for (glm::vec3& p : m.positions) {
      p.x *= spread;
      p.z *= spread;
    }
    for (uint32_t& id : m.primitive_ids)
      id += ids;
    scene.meshes.push_back(std::move(m));
  }
}

struct Rendered {
  GBuffer g;
  glm::mat4 to_world{1.0f};
  AoShading ao;
  // World position and normal of pixel (x, y).
  glm::vec3 position(int x, int y) const {
    const cv::Vec3f p = g.position.at<cv::Vec3f>(y, x);
    return glm::vec3(to_world * glm::vec4(p[0], p[1], p[2], 1.0f));
  }
  glm::vec3 normal(int x, int y) const {
    const cv::Vec3f n = g.normal.at<cv::Vec3f>(y, x);
    return glm::mat3(to_world) * glm::vec3(n[0], n[1], n[2]);
  }
  int object(int x, int y) const { return g.id.at<int>(y, x); }  // mesh index + 1
  float ao_at(int x, int y) const { return g.ao.at<float>(y, x); }
};

Rendered render(const Scene& scene, const std::string& model, const std::string& solid_angle,
                float elevation = 25.0f) {
  auto ctx = create_gl_context();
  Rasterizer raster(*ctx);
  raster.upload(scene);
  OrbitParams orbit;
  orbit.elevation_deg = elevation;
  Camera camera = make_orbit_camera(scene.framing_sphere(), orbit, kSize, kSize);
  fit_camera_depth(camera, scene);  // as `sylva render --ground`
  AoSettings settings;
  settings.model = parse_ao_model(model, "test");
  settings.alpha_rho = "0.3";
  settings.solid_angle = solid_angle == "exact" ? SolidAngleModel::Exact : SolidAngleModel::Paper;
  Rendered r;
  r.ao = scene_ao_shading(scene, settings, 1);
  RasterRequest request;
  request.targets = Target::Ao | Target::Position | Target::Normal | Target::Depth | Target::Id;
  request.id_kind = IdKind::Object;
  request.ao = r.ao;
  r.g = raster.render(camera, Lighting::three_point(), request);
  r.to_world = glm::inverse(camera.view);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float a = r.ao_at(x, y);
      EXPECT_TRUE(std::isfinite(a) && a >= 0.0f && a <= 1.0f) << a;
    }
  return r;
}

// What a non-foliage fragment gets: Eq. 7-8 of the crown, minus the ground plane's share of
// the sky for wood (`wood`), as the shader does.
float cpu_object(const AoShading& ao, const glm::vec3& x, const glm::vec3& n, bool wood = false) {
  float v = 1.0f;
  if (ao.crown_radius > 0.0f) {
    Sphere crown;
    crown.centre = ao.crown_centre;
    crown.radius = ao.crown_radius;
    ObjectOcclusion o;
    o.model = ao.exact_solid_angle ? SolidAngleModel::Exact : SolidAngleModel::Paper;
    v = object_visibility(crown, x, n, o);
  }
  if (wood && ao.ground_plane) v -= ground_plane_occlusion(x.y - ao.ground_y, n);
  return std::clamp(v, 0.0f, 1.0f);
}

TEST(AoObjects, GroundAndTrunkMatchObjectVisibilityOnTheCpu) {
  Scene scene = small_tree();
  add_ground_plane(scene, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  const int ground = int(scene.meshes.size());  // object id of the ground (last mesh)
  for (const char* mode : {"exact", "paper"}) {
    const Rendered r = render(scene, "hegeman-sphere", mode);
    ASSERT_GT(r.ao.crown_radius, 0.0f);
    // The crown is the sphere shell of hegeman-sphere.
    ASSERT_EQ(r.ao.centres.size(), 1u);
    EXPECT_NEAR(glm::length(r.ao.centres[0] - r.ao.crown_centre), 0.0f, 1e-4f);
    EXPECT_NEAR(1.0f / r.ao.inverse[0][0][0], r.ao.crown_radius, 1e-3f * r.ao.crown_radius);
    ASSERT_TRUE(r.ao.ground_plane);  // the flat --ground plane darkens the trunk too
    EXPECT_EQ(r.ao.ground_y, scene.meshes.back().positions[0].y);
    double max_diff = 0.0, near_sum = 0.0, far_sum = 0.0, trunk_sum = 0.0;
    int grounds = 0, trunks = 0, nears = 0, fars = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const int obj = r.object(x, y);
        if (obj != ground && obj != 2) continue;  // 2: the bark
        const glm::vec3 p = r.position(x, y), n = r.normal(x, y);
        const float cpu = cpu_object(r.ao, p, n, obj == 2);
        max_diff = std::max(max_diff, double(std::abs(cpu - r.ao_at(x, y))));
        if (obj == 2) {
          ++trunks;
          trunk_sum += r.ao_at(x, y);
          continue;
        }
        ++grounds;
        const glm::vec2 off(p.x - r.ao.crown_centre.x, p.z - r.ao.crown_centre.z);
        if (glm::length(off) < 0.5f * r.ao.crown_radius) near_sum += r.ao_at(x, y), ++nears;
        if (glm::length(off) > 2.5f * r.ao.crown_radius) far_sum += r.ao_at(x, y), ++fars;
      }
    // Kept in the test report (--gtest_output=json): the measured values.
    const std::string m = mode;
    RecordProperty("max_diff_" + m, std::to_string(max_diff));
    RecordProperty("ground_under_crown_" + m, std::to_string(nears ? near_sum / nears : 0.0));
    RecordProperty("ground_far_" + m, std::to_string(fars ? far_sum / fars : 0.0));
    EXPECT_GT(grounds, kSize * kSize / 10) << mode;
    EXPECT_GT(trunks, 5) << mode;
    EXPECT_LT(max_diff, 2e-3) << mode;
    ASSERT_GT(nears, 10) << mode;
    ASSERT_GT(fars, 10) << mode;
    // A soft shadow: darker right under the crown than far from it.
    EXPECT_LT(near_sum / nears, far_sum / fars - 0.1) << mode;
    EXPECT_GT(far_sum / fars, 0.9) << mode;
    // An upright trunk loses half its sky to the ground, and some more to the crown (0.16
    // with the exact solid angle).
    EXPECT_LT(trunk_sum / trunks, 0.5) << mode;
    EXPECT_GT(trunk_sum / trunks, 0.1) << mode;
  }
}

TEST(AoObjects, ExactSolidAngleDarkensMoreThanThePapersNearTheCrown) {
  Scene scene = small_tree();
  add_ground_plane(scene, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  const int ground = int(scene.meshes.size());
  const Rendered exact = render(scene, "hegeman-sphere", "exact");
  const Rendered paper = render(scene, "hegeman-sphere", "paper");
  int compared = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (exact.object(x, y) != ground) continue;
      // 2 pi (1 - cos b) >= pi sin^2 b: the exact angle occludes at least as much.
      EXPECT_LE(exact.ao_at(x, y), paper.ao_at(x, y) + 1e-5f);
      ++compared;
    }
  EXPECT_GT(compared, 100);
}

TEST(AoObjects, EllipsoidAndShellModelsUseTheSameCrownSphere) {
  Scene scene = small_tree();
  add_ground_plane(scene, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  const int ground = int(scene.meshes.size());
  const Rendered sphere = render(scene, "hegeman-sphere", "exact");
  for (const char* model : {"hegeman-ellipsoid", "hegeman-shells"}) {
    const Rendered r = render(scene, model, "exact");
    EXPECT_EQ(r.ao.crown_centre, sphere.ao.crown_centre) << model;
    EXPECT_EQ(r.ao.crown_radius, sphere.ao.crown_radius) << model;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        if (r.object(x, y) == ground) {
          ASSERT_EQ(r.ao_at(x, y), sphere.ao_at(x, y)) << model;
        }
  }
}

// Eq. 9 for each grass pixel, times the crown's occlusion when there is a crown.
void expect_grass_matches(const Rendered& r, int grass_object, double& bottom, double& top) {
  const float h = r.ao.grass_height;
  ASSERT_GT(h, 0.0f);
  double max_diff = 0.0, lo = 0.0, hi = 0.0;
  int n = 0, los = 0, his = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (r.object(x, y) != grass_object) continue;
      const glm::vec3 p = r.position(x, y), nr = r.normal(x, y);
      const float cpu = grass_visibility(p.y - r.ao.grass_ground, h, nr) * cpu_object(r.ao, p, nr);
      max_diff = std::max(max_diff, double(std::abs(cpu - r.ao_at(x, y))));
      ++n;
      const float share = (p.y - r.ao.grass_ground) / h;
      if (share < 0.3f) lo += r.ao_at(x, y), ++los;
      if (share > 0.7f) hi += r.ao_at(x, y), ++his;
    }
  EXPECT_GT(n, 50);
  EXPECT_LT(max_diff, 2e-3);
  ASSERT_GT(los, 5);
  ASSERT_GT(his, 5);
  bottom = lo / los;
  top = hi / his;
  ::testing::Test::RecordProperty("grass_max_diff", std::to_string(max_diff));
  ::testing::Test::RecordProperty("grass_roots", std::to_string(bottom));
  ::testing::Test::RecordProperty("grass_tips", std::to_string(top));
}

TEST(AoObjects, GrassPatchRisesFromRootToTip) {
  GrassOptions go;
  go.blades = 400;
  const Scene grass = make_grass(go);
  const Rendered r = render(grass, "hegeman-sphere", "exact", 20.0f);
  EXPECT_EQ(r.ao.crown_radius, 0.0f);  // no foliage: no crown, Eq. 9 alone
  EXPECT_EQ(r.ao.grass_ground, 0.0f);
  EXPECT_EQ(r.ao.grass_height, grass.bounds(Role::Grass).max.y);
  double bottom = 0, top = 0;
  expect_grass_matches(r, 1, bottom, top);
  EXPECT_LT(bottom + 0.2, top);
}

TEST(AoObjects, GrassUnderATreeIsAlsoOccludedByTheCrown) {
  Scene scene = small_tree();
  GrassOptions go;
  go.blades = 3000;
  merge(scene, make_grass(go), 8.0f);  // an 8 m x 8 m patch around the trunk
  const int grass = int(scene.meshes.size());
  const Rendered r = render(scene, "hegeman-sphere", "exact");
  ASSERT_GT(r.ao.crown_radius, 0.0f);
  double bottom = 0, top = 0;
  expect_grass_matches(r, grass, bottom, top);
  EXPECT_LT(bottom, top);
}

// The ground plane term is on only for flat ground: not without ground, not for a tilted one.
TEST(AoObjects, GroundPlaneOnlyForFlatGround) {
  AoSettings s;
  s.model = AoModel::HegemanEllipsoid;
  s.alpha_rho = "0.3";
  Scene scene = small_tree();
  EXPECT_FALSE(scene_ao_shading(scene, s, 1).ground_plane);
  add_ground_plane(scene, glm::vec4(0.5f));
  const AoShading flat = scene_ao_shading(scene, s, 1);
  EXPECT_TRUE(flat.ground_plane);
  EXPECT_EQ(flat.ground_y, scene.meshes.back().positions[1].y);
  scene.meshes.back().positions[1].y += 0.5f;  // one rim vertex raised: no longer a plane
  EXPECT_FALSE(scene_ao_shading(scene, s, 1).ground_plane);
}

TEST(AoObjects, SolidAngleParameter) {
  Scene scene = small_tree();
  AoSettings s;
  s.model = AoModel::HegemanSphere;
  s.alpha_rho = "0.3";
  s.solid_angle = SolidAngleModel::Paper;
  EXPECT_FALSE(scene_ao_shading(scene, s, 1).exact_solid_angle);
  s.solid_angle = SolidAngleModel::Exact;
  EXPECT_TRUE(scene_ao_shading(scene, s, 1).exact_solid_angle);
  s.solid_angle = static_cast<SolidAngleModel>(7);  // neither (a program's cast)
  try {
    scene_ao_shading(scene, s, 1);
    ADD_FAILURE() << "ao.solid_angle that is neither exact nor paper accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "ao.solid_angle");
  }
  // Neither foliage nor grass: hegeman-* has nothing to fit.
  s.solid_angle = SolidAngleModel::Exact;
  Scene bare;
  bare.meshes.push_back(scene.meshes[1]);  // the bark alone
  bare.materials = scene.materials;
  EXPECT_THROW(scene_ao_shading(bare, s, 1), InputError);
}

}  // namespace
}  // namespace sylva
