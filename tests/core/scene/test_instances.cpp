// Plants and instances: glTF nodes sharing meshes, repeated subtrees, "sylva_plant" markers
// and EXT_mesh_gpu_instancing become plants stored once with instances (core/scene/
// gltf_nodes.h); their bad input; the id layout; flattening; writing and reading back.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "core/random.h"
#include "core/scene/gltf_write.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "core/scene/point_tree.h"
#include "tests/core/scene/gltf_builder.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using test::GltfBuilder;
using Json = nlohmann::json;

constexpr size_t kGridTriangles = 2 * 10 * 6;  // a 10 x 6 grid: above kMinPlantTriangles

Scene load_text(const GltfBuilder& b, const std::string& name = "s.gltf") {
  const std::string path = test::temp_dir("instances") + "/" + name;
  test::write_file(path, b.text());
  return load_scene(path);
}

// The error message of loading `b`, or "" when it loads.
std::string load_error(const GltfBuilder& b) {
  try {
    load_text(b);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Json at(float x, float y, float z) {
  return {{"translation", {x, y, z}}};
}

TEST(Instances, NodesSharingAMeshAreOnePlantWithAnInstanceEach) {
  GltfBuilder b;
  b.grid_mesh("leafy", 10, 6);
  for (int i = 0; i < 3; ++i) {
    Json n = at(float(3 * i), 0, 0);
    n["mesh"] = 0;
    b.node(n);
  }
  const Scene s = load_text(b);
  ASSERT_TRUE(s.instanced());
  EXPECT_EQ(s.plant_count(), 1u);
  EXPECT_EQ(s.instance_count(), 3u);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), kGridTriangles);
  EXPECT_EQ(s.drawn_triangle_count(), 3 * kGridTriangles);
  // World bounds span every instance: x from 0 to 6 + 1.
  const Bounds w = s.bounds();
  EXPECT_FLOAT_EQ(w.min.x, 0.0f);
  EXPECT_FLOAT_EQ(w.max.x, 7.0f);
  EXPECT_FLOAT_EQ(w.max.y, 1.0f);
  const Scene flat = flatten(s);
  EXPECT_FALSE(flat.instanced());
  EXPECT_EQ(flat.triangle_count(), 3 * kGridTriangles);
  EXPECT_EQ(flat.bounds().max.x, w.max.x);
}

TEST(Instances, RepeatedSubtreesAreAPlantAndTheRestAnother) {
  GltfBuilder b;
  b.grid_mesh("bark", 10, 6);
  b.grid_mesh("leaves", 10, 6, 0.0f, 1.0f);
  b.grid_mesh("ground", 10, 6, -5.0f, -5.0f);
  for (int i = 0; i < 4; ++i) {
    const int tree = b.node(at(float(2 * i), 0, 1));
    b.node({{"mesh", 0}}, tree);
    b.node({{"mesh", 1}, {"translation", {0, 0.5, 0}}}, tree);
  }
  b.node({{"mesh", 2}, {"name", "ground"}});
  const Scene s = load_text(b);
  ASSERT_TRUE(s.instanced());
  ASSERT_EQ(s.plants.size(), 2u);  // the rest (ground) first, then the tree
  EXPECT_EQ(s.plants[0].meshes.size(), 1u);
  EXPECT_EQ(s.plants[1].meshes.size(), 2u);
  EXPECT_EQ(s.instances.size(), 5u);
  EXPECT_EQ(s.instances[0].plant, 0u);
  EXPECT_EQ(s.instances[0].transform, glm::mat4(1.0f));
  EXPECT_EQ(s.drawn_triangle_count(), 9 * kGridTriangles);
  // The leaves keep their place inside the plant (0.5 up from the bark).
  const Mesh& leaves = s.meshes[s.plants[1].meshes[1]];
  EXPECT_FLOAT_EQ(leaves.positions[0].y, 1.5f);
}

TEST(Instances, SmallRepeatedPartsStayInThePlantAroundThem) {
  GltfBuilder b;
  b.grid_mesh("leaf", 2, 2);  // 8 triangles: a leaf card, not a plant
  for (int i = 0; i < 5; ++i) {
    Json n = at(float(i), 0, 0);
    n["mesh"] = 0;
    b.node(n);
  }
  const Scene s = load_text(b);
  EXPECT_FALSE(s.instanced());
  EXPECT_EQ(s.meshes.size(), 5u);
  EXPECT_EQ(s.triangle_count(), 40u);
}

TEST(Instances, AMarkedNodeIsAPlantEvenPlacedOnce) {
  GltfBuilder b;
  b.grid_mesh("small", 2, 2);
  b.grid_mesh("other", 10, 6, 3.0f, 0.0f);
  b.node({{"mesh", 0}, {"name", "n"}, {"extras", {{"sylva_plant", "oak"}}}});
  b.node({{"mesh", 1}});
  const Scene s = load_text(b);
  ASSERT_TRUE(s.instanced());
  ASSERT_EQ(s.plants.size(), 2u);
  EXPECT_EQ(s.plants[1].name, "oak");
  EXPECT_EQ(s.instances.back().name, "n");
}

TEST(Instances, FilesWithoutRepeatsStayFlat) {
  const Scene fern = load_scene(test::fern_path());
  EXPECT_FALSE(fern.instanced());
  EXPECT_TRUE(fern.instances.empty());
  EXPECT_EQ(fern.instance_count(), 1u);
  EXPECT_EQ(fern.drawn_triangle_count(), fern.triangle_count());
}

// EXT_mesh_gpu_instancing on one node: TRANSLATION, ROTATION, SCALE per instance.
GltfBuilder gpu_instanced(int count, int cols = 10) {
  GltfBuilder b;
  b.grid_mesh("grid", cols, 6);
  std::vector<float> t, r, s;
  for (int i = 0; i < count; ++i) {
    t.insert(t.end(), {float(2 * i), 0.0f, 0.0f});
    r.insert(r.end(), {0.0f, 0.0f, 0.0f, 1.0f});
    s.insert(s.end(), {1.0f, 1.0f + float(i), 1.0f});
  }
  Json ext = {{"attributes",
               {{"TRANSLATION", b.floats(t, "VEC3", 3)},
                {"ROTATION", b.floats(r, "VEC4", 4)},
                {"SCALE", b.floats(s, "VEC3", 3)}}}};
  b.node({{"mesh", 0}, {"name", "grid"}, {"extensions", {{"EXT_mesh_gpu_instancing", ext}}}});
  b.json()["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.json()["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  return b;
}

TEST(Instances, GpuInstancingLoadsEveryInstance) {
  const Scene s = load_text(gpu_instanced(4));
  ASSERT_TRUE(s.instanced());
  EXPECT_EQ(s.instance_count(), 4u);
  EXPECT_EQ(s.triangle_count(), kGridTriangles);
  EXPECT_EQ(s.drawn_triangle_count(), 4 * kGridTriangles);
  const Bounds w = s.bounds();
  EXPECT_FLOAT_EQ(w.max.x, 7.0f);  // the last instance at x = 6, one unit wide
  EXPECT_FLOAT_EQ(w.max.y, 4.0f);  // scaled 4 in y
}

TEST(Instances, SmallGpuInstancedMeshesArePlacedLikeAnyMesh) {
  const Scene s = load_text(gpu_instanced(3, 2));  // 24 triangles
  EXPECT_FALSE(s.instanced());
  EXPECT_EQ(s.triangle_count(), 3u * 24u);
}

TEST(Instances, BadGpuInstancingIsAnError) {
  auto with = [](const std::function<void(GltfBuilder&)>& change) {
    GltfBuilder b = gpu_instanced(3);
    change(b);
    return load_error(b);
  };
  auto attributes = [](GltfBuilder& b) -> Json& {
    return b.json()["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  };
  EXPECT_NE(with([&](GltfBuilder& b) {
              const std::vector<float> v(6, 0.0f);
              attributes(b)["TRANSLATION"] = b.floats(v, "VEC2", 2);
            }).find("TRANSLATION must be a VEC3"),
            std::string::npos);
  EXPECT_NE(with([&](GltfBuilder& b) {
              const std::vector<float> v(8, 0.5f);
              attributes(b)["ROTATION"] = b.floats(v, "VEC4", 4);  // 2 entries, not 3
            }).find("ROTATION has 2 entries"),
            std::string::npos);
  EXPECT_NE(with([&](GltfBuilder& b) {
              const std::vector<uint8_t> v(12, 255);
              attributes(b)["ROTATION"] = b.accessor(v.data(), v.size(), 5121, 3, "VEC4", true);
            }).find("ROTATION must be a VEC4 of floats or normalized bytes/shorts"),
            std::string::npos);
  EXPECT_NE(with([&](GltfBuilder& b) {
              attributes(b)["SCALE"] = 999;
            }).find("SCALE refers to a missing accessor"),
            std::string::npos);
  EXPECT_NE(with([&](GltfBuilder& b) {
              const std::vector<float> v(12, 0.0f);
              attributes(b)["ROTATION"] = b.floats(v, "VEC4", 4);
            }).find("ROTATION 0 is not a unit quaternion"),
            std::string::npos);
  EXPECT_NE(with([&](GltfBuilder& b) { attributes(b) = Json::object(); }).find("needs TRANSLATION"),
            std::string::npos);
  // Normalized signed shorts are a valid rotation.
  EXPECT_EQ(with([&](GltfBuilder& b) {
              const std::vector<int16_t> v = {0, 0, 0, 32767, 0, 0, 0, 32767, 0, 0, 0, 32767};
              attributes(b)["ROTATION"] = b.accessor(v.data(), v.size() * 2, 5122, 3, "VEC4", true);
            }),
            "");
}

TEST(Instances, ZeroScaleInstancesAreLeftOutWithAWarning) {
  GltfBuilder b;
  b.grid_mesh("grid", 10, 6);
  b.node({{"mesh", 0}, {"name", "a"}});
  b.node({{"mesh", 0}, {"name", "hidden"}, {"scale", {0, 0, 0}}});
  const Scene s = load_text(b);
  ASSERT_TRUE(s.instanced());
  EXPECT_EQ(s.instance_count(), 1u);
  ASSERT_FALSE(s.report.warnings.empty());
  EXPECT_NE(s.report.warnings[0].find("'hidden'"), std::string::npos);
}

// Two plants, foliage clusters 1..2 and 1..3 with wood: what each instance adds.
Scene two_plant_scene() {
  Scene s;
  for (int p = 0; p < 2; ++p) {
    Mesh m;
    m.name = p == 0 ? "a" : "b";
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    m.indices = {0, 1, 2, 1, 3, 2, 0, 1, 2};
    m.roles = {Role::Foliage, Role::Foliage, Role::Wood};
    s.meshes.push_back(m);
    s.plants.push_back({m.name, {uint32_t(p)}, {}});
  }
  s.instances = {{0, glm::mat4(1.0f), "a0"},
                 {1, glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)), "b0"},
                 {0, glm::translate(glm::mat4(1.0f), glm::vec3(4, 0, 0)), "a1"}};
  LoadOptions keep;
  finish_scene(s, keep, true);
  s.meshes[0].cluster_ids = {1, 2, 3};  // foliage 1, 2; wood 3
  s.meshes[1].cluster_ids = {2, 3, 4};  // foliage up to 3; wood 4
  return s;
}

TEST(Instances, EachInstanceHasItsOwnIdsAndTheWoodOneCluster) {
  const Scene s = two_plant_scene();
  const IdLayout l = id_layout(s);
  ASSERT_EQ(l.bases.size(), 3u);
  // Primitive ids: the quad is one primitive (1) and the wood triangle shares its vertices.
  EXPECT_EQ(l.bases[1].primitive, 1u);
  EXPECT_EQ(l.bases[2].primitive, 2u);
  EXPECT_EQ(l.bases[1].cluster, 2u);
  EXPECT_EQ(l.bases[2].cluster, 5u);
  EXPECT_EQ(l.bases[2].object, 2u);
  EXPECT_EQ(l.branch_cluster, 8u);  // 2 + 3 + 2 foliage clusters, + 1
  EXPECT_EQ(s.branch_cluster_id(), 8u);
  // Flattening gives the meshes the ids the id buffer has.
  const Scene flat = flatten(s);
  ASSERT_EQ(flat.meshes.size(), 3u);
  EXPECT_EQ(flat.meshes[2].cluster_ids, (std::vector<uint32_t>{6, 7, 8}));
  EXPECT_EQ(flat.meshes[1].cluster_ids, (std::vector<uint32_t>{4, 5, 8}));
  EXPECT_EQ(flat.meshes[2].name, "a1/a");
  EXPECT_FLOAT_EQ(flat.meshes[2].positions[1].x, 5.0f);
  // A flat scene keeps its own ids.
  const IdLayout f = id_layout(flat);
  EXPECT_EQ(f.branch_cluster, 0u);
  EXPECT_EQ(f.max_cluster, 8u);
}

TEST(Instances, WrittenAndReadBackKeepsTheInstancing) {
  Scene s = two_plant_scene();
  s.instances[2].transform = glm::scale(s.instances[2].transform, glm::vec3(-1, 2, 1));
  const std::string path = test::temp_dir("instances") + "/two.glb";
  write_glb(s, path);
  const Scene r = load_scene(path);
  ASSERT_TRUE(r.instanced());
  ASSERT_EQ(r.plants.size(), 2u);
  EXPECT_EQ(r.plants[0].name, "a");
  EXPECT_EQ(r.plants[1].name, "b");
  ASSERT_EQ(r.instances.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.instances[i].plant, s.instances[i].plant);
    EXPECT_EQ(r.instances[i].transform, s.instances[i].transform);
    EXPECT_EQ(r.instances[i].name, s.instances[i].name);
  }
  // Each mesh mixes foliage and wood: written as a primitive per role, read as a mesh each.
  EXPECT_EQ(r.meshes.size(), 4u);
  EXPECT_EQ(r.plants[0].meshes.size(), 2u);
  EXPECT_EQ(r.drawn_triangle_count(), s.drawn_triangle_count());
  if (test::gltf_validator_installed()) {
    const test::RunResult v = test::validate_gltf(path);
    EXPECT_EQ(v.status, 0) << v.output;
  }
}

TEST(Instances, ValidationRefusesBrokenInstancing) {
  auto error = [](const std::function<void(Scene&)>& change) {
    Scene s = two_plant_scene();
    change(s);
    return test::where_of([&] { validate_instances(s, "memory"); });
  };
  EXPECT_EQ(error([](Scene&) {}), "no error");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].plant = 7; }), "memory");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].transform[0][0] = NAN; }), "memory");
  EXPECT_EQ(error([](Scene& s) { s.instances[0].transform = glm::mat4(0.0f); }), "memory");
  EXPECT_EQ(error([](Scene& s) { s.plants[1].meshes = {0}; }), "memory");
  EXPECT_EQ(error([](Scene& s) { s.plants[1].meshes.clear(); }), "memory");
}

TEST(FileCameras, ReadWithTheirNodesAndImpossibleOnesLeftOut) {
  GltfBuilder b;
  b.grid_mesh("grid", 10, 6);
  b.node({{"mesh", 0}});
  b.json()["cameras"] = {
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}},
      {{"type", "orthographic"},
       {"orthographic", {{"xmag", 2.0}, {"ymag", -1.5}, {"znear", 0.0}, {"zfar", 10.0}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}},
      {{"type", "orthographic"},
       {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 5.0}, {"zfar", 1.0}}}}};
  const float s2 = std::sqrt(0.5f);
  b.node(
      {{"name", "side"}, {"camera", 0}, {"translation", {1, 2, 3}}, {"rotation", {0, s2, 0, s2}}});
  b.node({{"camera", 1}, {"translation", {0, 5, 0}}, {"scale", {2, 2, 2}}});
  b.node({{"name", "zero fov"}, {"camera", 2}});
  b.node({{"name", "far before near"}, {"camera", 3}});
  const Scene s = load_text(b);
  ASSERT_EQ(s.cameras.size(), 2u);
  const SceneCamera& side = s.cameras[0];
  EXPECT_EQ(side.name, "side");
  EXPECT_FALSE(side.orthographic);
  EXPECT_FLOAT_EQ(side.yfov, 0.8f);
  EXPECT_EQ(side.zfar, 0.0f);  // infinite
  EXPECT_EQ(glm::vec3(side.to_world[3]), glm::vec3(1, 2, 3));
  // Turned 90 degrees about +Y: the camera's -Z looks along world -X.
  const glm::vec3 forward = -glm::vec3(side.to_world[2]);
  EXPECT_NEAR(forward.x, -1.0f, 1e-6f);
  const SceneCamera& top = s.cameras[1];
  EXPECT_EQ(top.name, "camera 1");
  EXPECT_TRUE(top.orthographic);
  EXPECT_FLOAT_EQ(top.ymag, 1.5f);
  EXPECT_FLOAT_EQ(top.zfar, 10.0f);
  EXPECT_NEAR(glm::length(glm::vec3(top.to_world[0])), 1.0f, 1e-6f);  // scale removed
  const std::vector<std::string> w = s.report.warning_lines();
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("'zero fov': yfov must be in (0, pi); left out (and 1 more like it)"),
            std::string::npos)
      << w[0];
}

TEST(PointTree, ExtentsEqualMovingEveryPoint) {
  const Scene fern = load_scene(test::fern_path());
  std::vector<glm::vec3> points;
  for (const Mesh& m : fern.meshes)
    points.insert(points.end(), m.positions.begin(), m.positions.end());
  const PointTree tree(points);
  uint64_t state = 11;
  auto u = [&] { return float(uniform01(state)); };
  for (int i = 0; i < 40; ++i) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(20 * u() - 10, u(), 20 * u() - 10));
    t = glm::rotate(t, 6.3f * u(), glm::normalize(glm::vec3(u() - 0.5f, u(), u() - 0.5f)));
    t = glm::scale(t, glm::vec3(0.5f + u(), 0.5f + u(), i % 3 == 0 ? -1.0f : 0.5f + u()));
    const glm::dmat4 d(t);
    Bounds want;
    const glm::vec3 c(u(), u(), u());
    float far = 0.0f;
    for (const glm::vec3& p : points) {
      const glm::vec3 q(d * glm::dvec4(p, 1.0));
      want.extend(q);
      far = std::max(far, glm::dot(q - c, q - c));
    }
    const Bounds got = tree.moved_bounds(d);
    EXPECT_EQ(got.min, want.min) << i;
    EXPECT_EQ(got.max, want.max) << i;
    EXPECT_EQ(tree.max_distance2(d, c), far) << i;
  }
  EXPECT_TRUE(PointTree({}).moved_bounds(glm::dmat4(1.0)).empty());
}

}  // namespace
}  // namespace sylva
