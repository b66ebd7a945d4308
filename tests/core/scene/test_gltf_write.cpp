// Writing .glb and reading it back: geometry, materials, textures, hierarchy and roles
// survive; the container follows the glTF rules the validator checks; failures leave no
// file behind.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
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

// Per-vertex data as `sylva bake` writes it: ka and replacement normals for every mesh.
GlbVertexData baked_data(const Scene& s) {
  GlbVertexData d;
  for (const Mesh& m : s.meshes) {
    std::vector<glm::vec3> normals;
    std::vector<float> ka;
    for (size_t v = 0; v < m.positions.size(); ++v) {
      normals.push_back(glm::vec3(0.0f, 2.0f, float(v)));  // not unit: written unit
      ka.push_back(0.25f + 0.125f * float(v % 7));
    }
    d.normals.push_back(normals);
    d.ka.push_back(ka);
  }
  d.note_json = R"({"ka_min": 0.25})";
  return d;
}

// The byte offset in the file of accessor `a`'s first element (tightly packed floats).
size_t accessor_offset(const std::string& bytes, const Json& j, size_t a) {
  uint32_t json_len = 0;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  const Json& acc = j["accessors"][a];
  const Json& view = j["bufferViews"][acc["bufferView"].get<size_t>()];
  return 20 + json_len + 8 + view["byteOffset"].get<size_t>() + acc.value("byteOffset", size_t(0));
}

std::vector<float> accessor_floats(const std::string& bytes, const Json& j, size_t a) {
  const Json& acc = j["accessors"][a];
  const std::string type = acc["type"];
  const size_t comps = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
  std::vector<float> out(acc["count"].get<size_t>() * comps);
  std::memcpy(out.data(), bytes.data() + accessor_offset(bytes, j, a), out.size() * 4);
  return out;
}

TEST(GltfWrite, AmbientRoundTrip) {
  const Scene in = small_scene();
  const GlbVertexData data = baked_data(in);
  const std::string path = test::temp_dir("ambient") + "/baked.glb";
  write_glb(in, path, &data);

  const std::string bytes = test::read_file(path);
  uint32_t bin_length = 0;
  const Json j = glb_json(bytes, bin_length);
  EXPECT_EQ(j["scenes"][0]["extras"]["sylva_baked"]["ka_min"], 0.25);
  ASSERT_EQ(j["meshes"].size(), in.meshes.size());
  for (size_t m = 0; m < in.meshes.size(); ++m) {
    const Json& mesh = j["meshes"][m];
    EXPECT_EQ(mesh["extras"]["sylva_color_0"], "ambient");
    for (const Json& prim : mesh["primitives"]) {  // the mixed mesh has two, sharing attributes
      const Json& at = prim["attributes"];
      EXPECT_EQ(j["accessors"][at["_AMBIENT"].get<size_t>()]["type"], "SCALAR");
      EXPECT_EQ(j["accessors"][at["COLOR_0"].get<size_t>()]["type"], "VEC3");
      const std::vector<float> ka = accessor_floats(bytes, j, at["_AMBIENT"]);
      const std::vector<float> c0 = accessor_floats(bytes, j, at["COLOR_0"]);
      const std::vector<float> c1 = accessor_floats(bytes, j, at["COLOR_1"]);
      const std::vector<float> n = accessor_floats(bytes, j, at["NORMAL"]);
      EXPECT_EQ(ka, data.ka[m]);
      for (size_t v = 0; v < ka.size(); ++v) {
        const glm::vec4 own = in.meshes[m].colors[v];
        EXPECT_EQ(glm::vec4(c1[4 * v], c1[4 * v + 1], c1[4 * v + 2], c1[4 * v + 3]), own);
        for (int c = 0; c < 3; ++c)
          EXPECT_FLOAT_EQ(c0[3 * v + size_t(c)], own[c] * ka[v]);  // colour x ka
        const glm::vec3 nv(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
        EXPECT_NEAR(glm::length(nv), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(nv - glm::normalize(data.normals[m][v])), 0.0f, 1e-6f);
      }
    }
  }

  // Back in Sylva: ka from _AMBIENT, the real colours from COLOR_1, the baked normals.
  const Scene out = load_scene(path);
  ASSERT_EQ(out.meshes.size(), 4u);  // the mixed mesh reads back as one mesh per role
  const size_t source[4] = {0, 1, 2, 2};
  for (size_t m = 0; m < 4; ++m) {
    const Mesh& a = in.meshes[source[m]];
    const Mesh& b = out.meshes[m];
    EXPECT_EQ(b.ka, data.ka[source[m]]) << b.name;
    EXPECT_TRUE(b.outward_normals) << b.name;
    EXPECT_EQ(b.colors, a.colors) << b.name;
    for (size_t v = 0; v < b.normals.size(); ++v)
      EXPECT_NEAR(glm::length(b.normals[v] - glm::normalize(data.normals[source[m]][v])), 0.0f,
                  1e-6f);
  }

  // A scene that carries ka writes it again without extra data: baked files survive a rewrite.
  const std::string again = test::temp_dir("ambient") + "/again.glb";
  write_glb(out, again);
  const Scene twice = load_scene(again);
  for (size_t m = 0; m < 4; ++m) {
    EXPECT_EQ(twice.meshes[m].ka, out.meshes[m].ka);
    EXPECT_EQ(twice.meshes[m].colors, out.meshes[m].colors);
  }
}

TEST(GltfWrite, AmbientOutsideUnitRangeIsInputError) {
  const Scene in = small_scene();
  const GlbVertexData data = baked_data(in);
  const std::string dir = test::temp_dir("ambient-bad");
  write_glb(in, dir + "/good.glb", &data);
  const std::string good = test::read_file(dir + "/good.glb");
  uint32_t bin_length = 0;
  const Json j = glb_json(good, bin_length);
  const size_t at =
      accessor_offset(good, j, j["meshes"][1]["primitives"][0]["attributes"]["_AMBIENT"]);
  for (float bad : {1.5f, -0.25f, std::nanf(""), std::numeric_limits<float>::infinity()}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + at + 4, &bad, 4);  // vertex 1 of mesh "leaves"
    const std::string path = dir + "/bad.glb";
    test::write_file(path, bytes);
    try {
      load_scene(path);
      FAIL() << "accepted _AMBIENT " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path, 0), 0u) << what;  // names the file first
      EXPECT_NE(what.find("_AMBIENT"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace sylva
