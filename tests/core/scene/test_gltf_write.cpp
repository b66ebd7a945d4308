// Writing .glb and reading it back: geometry, materials, textures, hierarchy and roles
// survive; the container follows the glTF rules the validator checks; failures leave no
// file behind.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/scene/gltf_read.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using Json = nlohmann::json;

Mesh quad(const std::string& name, float x, int material) {
  Mesh m;
  m.name = name;
  m.material = material;
  m.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0.5f}, {x, 1, 0.5f}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.colors = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 0.5f}, {1, 1, 1, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// Trunk (wood), two leaves in one mesh (foliage), a mixed mesh; a texture with alpha;
// a three-branch hierarchy.
Scene small_scene() {
  Scene s;
  Texture tex{"leaf_tex", 3, 2, {}};
  for (int i = 0; i < 6; ++i)
    tex.rgba.insert(tex.rgba.end(), {uint8_t(40 * i), 200, 7, uint8_t(i * 50)});
  s.textures.push_back(tex);
  s.materials.push_back(
      Material{"bark", glm::vec4(0.4f, 0.3f, 0.2f, 1.0f), -1, AlphaMode::Opaque, 0.5f, false});
  s.materials.push_back(Material{"leaf", glm::vec4(1.0f), 0, AlphaMode::Mask, 0.3f, true});
  s.meshes.push_back(quad("trunk", 0, 0));
  s.meshes.back().roles = {Role::Wood, Role::Wood};
  Mesh leaves = quad("leaves", 2, 1);
  Mesh second = quad("", 4, 1);
  for (size_t v = 0; v < 4; ++v) {
    leaves.positions.push_back(second.positions[v]);
    leaves.uvs.push_back(second.uvs[v]);
    leaves.colors.push_back(second.colors[v]);
  }
  for (uint32_t i : second.indices)
    leaves.indices.push_back(i + 4);
  leaves.roles.assign(4, Role::Foliage);
  s.meshes.push_back(leaves);
  Mesh mixed = quad("mixed", 6, -1);
  mixed.roles = {Role::Ground, Role::Other};
  s.meshes.push_back(mixed);
  s.hierarchy.branch_parent = {-1, 0, 0};
  s.hierarchy.branch_diameter = {0.2f, 0.05f, 0.04f};
  s.hierarchy.leaf_branch = {1, 2};
  s.report.source = "test";
  finish_scene(s, {}, true);
  return s;
}

Json glb_json(const std::string& bytes, uint32_t& bin_length) {
  uint32_t json_len = 0;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  bin_length = 0;
  if (bytes.size() > 20 + json_len) std::memcpy(&bin_length, bytes.data() + 20 + json_len, 4);
  return Json::parse(bytes.substr(20, json_len));
}

TEST(GltfWrite, RoundTripPreservesEverything) {
  const Scene in = small_scene();
  const std::string path = test::temp_dir("write") + "/plant.glb";
  write_glb(in, path);
  const Scene out = read_gltf(path);

  ASSERT_EQ(out.meshes.size(), 4u);  // the mixed-role mesh becomes one mesh per role
  EXPECT_EQ(out.meshes[0].name, "trunk");
  EXPECT_EQ(out.meshes[2].name, "mixed[0]");
  EXPECT_EQ(out.meshes[3].name, "mixed[1]");
  for (size_t m = 0; m < 2; ++m) {
    const Mesh& a = in.meshes[m];
    const Mesh& b = out.meshes[m];
    EXPECT_EQ(a.indices, b.indices);
    EXPECT_EQ(a.material, b.material);
    EXPECT_EQ(a.roles, b.roles);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t v = 0; v < a.positions.size(); ++v) {
      EXPECT_EQ(a.positions[v], b.positions[v]);
      EXPECT_EQ(a.uvs[v], b.uvs[v]);
      EXPECT_EQ(a.colors[v], b.colors[v]);
      EXPECT_NEAR(glm::length(b.normals[v] - a.normals[v]), 0.0f, 1e-6f);
    }
  }
  EXPECT_EQ(out.meshes[2].roles, std::vector<Role>{Role::Ground});
  EXPECT_EQ(out.meshes[3].roles, std::vector<Role>{Role::Other});

  ASSERT_EQ(out.materials.size(), 2u);
  EXPECT_EQ(out.materials[0].name, "bark");
  EXPECT_EQ(out.materials[0].base_color, in.materials[0].base_color);
  EXPECT_EQ(out.materials[0].base_color_texture, -1);
  EXPECT_EQ(out.materials[1].alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(out.materials[1].alpha_cutoff, 0.3f);
  EXPECT_TRUE(out.materials[1].double_sided);
  ASSERT_EQ(out.textures.size(), 1u);
  EXPECT_EQ(out.textures[0].width, 3);
  EXPECT_EQ(out.textures[0].height, 2);
  EXPECT_EQ(out.textures[0].rgba, in.textures[0].rgba);  // PNG is lossless, RGBA order kept
  EXPECT_EQ(out.textures[0].name, "leaf_tex");

  EXPECT_EQ(out.hierarchy.branch_parent, in.hierarchy.branch_parent);
  EXPECT_EQ(out.hierarchy.branch_diameter, in.hierarchy.branch_diameter);
  EXPECT_EQ(out.hierarchy.leaf_branch, in.hierarchy.leaf_branch);

  // Through the full loader, roles come from the file in auto mode only.
  const Scene loaded = load_scene(path);
  EXPECT_EQ(loaded.report.foliage_rule, "sylva_role extras");
  EXPECT_EQ(loaded.meshes[0].roles[0], Role::Wood);
  EXPECT_EQ(loaded.max_primitive_id(), 5u);
  const Scene by_name = load_scene(path, {"leaf"});
  EXPECT_EQ(by_name.meshes[0].roles[0], Role::Wood);  // named "trunk"
}

TEST(GltfWrite, ContainerFollowsGltfRules) {
  const std::string path = test::temp_dir("rules") + "/plant.glb";
  Scene s = small_scene();
  s.meshes[0].normals[0] = {0, 0, 3};  // e.g. an encoded ambient coefficient: written unit
  write_glb(s, path);
  const std::string bytes = test::read_file(path);
  ASSERT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 8, 4);
  EXPECT_EQ(length, bytes.size());
  EXPECT_EQ(bytes.size() % 4, 0u);
  uint32_t bin_length = 0;
  const Json j = glb_json(bytes, bin_length);
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_EQ(j["scene"], 0);
  EXPECT_EQ(j["buffers"][0]["byteLength"], bin_length);
  for (const Json& v : j["bufferViews"]) {
    EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
    EXPECT_LE(v["byteOffset"].get<size_t>() + v["byteLength"].get<size_t>(), bin_length);
  }
  for (const Json& mesh : j["meshes"]) {
    for (const Json& prim : mesh["primitives"]) {
      const Json& pos = j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
      EXPECT_TRUE(pos.contains("min"));
      EXPECT_TRUE(pos.contains("max"));
      EXPECT_EQ(j["accessors"][prim["indices"].get<size_t>()]["componentType"], 5123);
    }
  }
  EXPECT_EQ(j["images"][0]["mimeType"], "image/png");
  EXPECT_EQ(j["samplers"].size(), 1u);
  EXPECT_FALSE(j["materials"][0].contains("alphaCutoff"));  // only with MASK
  const Scene back = read_gltf(path);
  EXPECT_NEAR(back.meshes[0].normals[0].z, 1.0f, 1e-6f);
}

TEST(GltfWrite, LargeMeshUses32BitIndices) {
  Scene s;
  Mesh m;
  m.name = "grid";
  const uint32_t n = 300;  // 90,000 vertices
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x)
      m.positions.push_back({float(x), float(y), 0});
  for (uint32_t y = 0; y + 1 < n; ++y)
    for (uint32_t x = 0; x + 1 < n; ++x) {
      const uint32_t i = y * n + x;
      m.indices.insert(m.indices.end(), {i, i + 1, i + n + 1, i, i + n + 1, i + n});
    }
  s.meshes.push_back(m);
  finish_scene(s, {});
  const std::string path = test::temp_dir("large") + "/grid.glb";
  write_glb(s, path);
  uint32_t bin_length = 0;
  const Json j = glb_json(test::read_file(path), bin_length);
  EXPECT_EQ(
      j["accessors"][j["meshes"][0]["primitives"][0]["indices"].get<size_t>()]["componentType"],
      5125);
  const Scene back = load_scene(path);
  EXPECT_EQ(back.meshes[0].indices, s.meshes[0].indices);
}

TEST(GltfWrite, FernRoundTrip) {
  const Scene fern = load_scene(test::fern_path());
  const std::string path = test::temp_dir("fern") + "/fern.glb";
  write_glb(fern, path);
  const Scene back = load_scene(path);
  EXPECT_EQ(back.triangle_count(), fern.triangle_count());
  EXPECT_EQ(back.max_primitive_id(), fern.max_primitive_id());
  EXPECT_EQ(back.report.foliage_rule, "sylva_role extras");
  ASSERT_EQ(back.textures.size(), 1u);
  EXPECT_EQ(back.textures[0].rgba, fern.textures[0].rgba);
  EXPECT_EQ(back.bounds().min, fern.bounds().min);
  EXPECT_EQ(back.bounds().max, fern.bounds().max);
}

TEST(GltfWrite, FailureLeavesNothing) {
  const Scene s = small_scene();
  const std::string dir = test::temp_dir("fail");
  try {
    write_glb(s, dir + "/missing/plant.glb");
    FAIL() << "wrote into a missing folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
  }
  std::filesystem::create_directory(dir + "/taken.glb");
  EXPECT_THROW(write_glb(s, dir + "/taken.glb"), InputError);
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    files += entry.is_regular_file();
  EXPECT_EQ(files, 0u);  // no temporary left behind
}

}  // namespace
}  // namespace sylva
