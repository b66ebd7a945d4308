// Hostile and broken scene files: each must end in an InputError naming the file, never a
// crash, an abort or a hang. Small glTF files are built here from a JSON template (also used
// for one test of well-formed files: node transforms and primitive modes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "core/scene/gltf_limits.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using Json = nlohmann::json;

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v =
        uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 | uint8_t(in[i + 2]);
    for (int s = 18; s >= 0; s -= 6)
      out += k[(v >> s) & 63];
  }
  if (i + 1 == in.size()) {
    const uint32_t v = uint32_t(uint8_t(in[i])) << 16;
    out += std::string{k[(v >> 18) & 63], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8;
    out += std::string{k[(v >> 18) & 63], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// A one-mesh glTF: float positions, then uint16 indices (4-byte aligned), in a data URI.
Json mesh_gltf(const std::vector<float>& p, const std::vector<uint16_t>& idx) {
  const size_t pos_bytes = p.size() * 4, idx_bytes = idx.size() * 2;
  std::string bin(pos_bytes + (idx_bytes + 3) / 4 * 4, '\0');
  std::memcpy(bin.data(), p.data(), pos_bytes);
  std::memcpy(bin.data() + pos_bytes, idx.data(), idx_bytes);
  Json j = Json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5123, "type": "SCALAR"}]
  })");
  j["accessors"][0]["count"] = p.size() / 3;
  j["accessors"][1]["count"] = idx.size();
  j["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos_bytes}},
                      {{"buffer", 0}, {"byteOffset", pos_bytes}, {"byteLength", idx_bytes}}};
  j["buffers"] = {
      {{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
  return j;
}

Json triangle(const float p[9], const uint16_t idx[3]) {
  return mesh_gltf(std::vector<float>(p, p + 9), std::vector<uint16_t>(idx, idx + 3));
}

Json good_triangle() {
  static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  static const uint16_t idx[3] = {0, 1, 2};
  return triangle(p, idx);
}

std::string write_gltf(const Json& j, const std::string& name = "t.gltf") {
  const std::string path = test::temp_dir("bad") + "/" + name;
  test::write_file(path, j.dump());
  return path;
}

// Loads and expects an InputError whose message names the file (and `needle` if given).
void expect_input_error(const std::string& path, const std::string& needle = "") {
  try {
    load_scene(path);
    ADD_FAILURE() << "loaded without error: " << path;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    if (!needle.empty()) {
      EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
  }
}

// Counts only a hostile file has are refused on the JSON, before tinygltf allocates for them:
// 100,000 empty meshes, a million-node list, an accessor of 2^31 elements.
TEST(BadInput, CountLimitsBeforeAllocation) {
  Json j = good_triangle();
  Json meshes = Json::array();
  for (int i = 0; i < 100000; ++i)
    meshes.push_back({{"primitives", Json::array()}});
  j["meshes"] = meshes;
  expect_input_error(write_gltf(j, "meshes.gltf"), "too many meshes: 100000 (at most 65536)");
  j = good_triangle();
  j["nodes"] = Json::array();
  for (int i = 0; i < (1 << 20) + 1; ++i)
    j["nodes"].push_back(Json::object());
  expect_input_error(write_gltf(j, "nodes.gltf"), "too many nodes");
  j = good_triangle();
  j["accessors"][0]["count"] = 2147483648.0;
  expect_input_error(write_gltf(j, "count.gltf"), "accessor 0: count");
  j = good_triangle();
  j["accessors"][1]["count"] = -1;
  expect_input_error(write_gltf(j, "negative.gltf"), "accessor 1: count");
  // At the limits, the files load (65,536 meshes, of which one is drawn).
  j = good_triangle();
  for (int i = 1; i < int(GltfLimits::kMaxMeshes); ++i)
    j["meshes"].push_back({{"primitives", Json::array()}});
  EXPECT_EQ(load_scene(write_gltf(j, "limit.gltf")).triangle_count(), 1u);
}

TEST(BadInput, TemplateIsGood) {
  Scene s = load_scene(write_gltf(good_triangle()));
  EXPECT_EQ(s.triangle_count(), 1u);
}

TEST(BadInput, TruncatedFern) {
  const std::string bytes = test::read_file(test::fern_path());
  ASSERT_GT(bytes.size(), 100000u);
  const std::string dir = test::temp_dir("trunc");
  for (size_t len : {size_t(1), size_t(5), size_t(12), size_t(19), size_t(20), size_t(100),
                     size_t(4000), bytes.size() / 2, bytes.size() - 1}) {
    const std::string path = dir + "/fern_" + std::to_string(len) + ".glb";
    test::write_file(path, bytes.substr(0, len));
    expect_input_error(path, len >= 12 ? "truncated" : "");
  }
}

TEST(BadInput, EmptyMissingDirectoryWrongExtension) {
  const std::string dir = test::temp_dir("misc");
  for (const char* name : {"empty.glb", "empty.gltf", "empty.obj", "empty.stl"}) {
    test::write_file(dir + "/" + name, "");
    expect_input_error(dir + "/" + name, "empty");
  }
  expect_input_error(dir + "/nope.glb", "no such file");
  expect_input_error(dir, "directory");
  test::write_file(dir + "/scene.txt", "hello");
  expect_input_error(dir + "/scene.txt", ".glb");
  test::write_file(dir + "/json.glb", good_triangle().dump());
  expect_input_error(dir + "/json.glb", "magic");
  test::write_file(dir + "/junk.ply", "this is not a mesh");
  expect_input_error(dir + "/junk.ply");
}

TEST(BadInput, CorruptJson) {
  std::string text = good_triangle().dump();
  const std::string dir = test::temp_dir("json");
  test::write_file(dir + "/cut.gltf", text.substr(0, text.size() / 2));
  expect_input_error(dir + "/cut.gltf", "JSON");
  test::write_file(dir + "/array.gltf", "[1, 2, 3]");
  expect_input_error(dir + "/array.gltf");
  Json wrong_type = good_triangle();
  wrong_type["accessors"][0]["count"] = "three";
  expect_input_error(write_gltf(wrong_type));
}

TEST(BadInput, IndexOutOfRange) {
  static const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  static const uint16_t idx[3] = {0, 1, 7};
  expect_input_error(write_gltf(triangle(p, idx)), "out of range");
}

TEST(BadInput, NanAndInfPositions) {
  const float nan_p[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
  const float inf_p[9] = {0, 0, 0, 1, 0, 0, 0, INFINITY, 0};
  static const uint16_t idx[3] = {0, 1, 2};
  expect_input_error(write_gltf(triangle(nan_p, idx)), "NaN");
  expect_input_error(write_gltf(triangle(inf_p, idx)), "NaN");
}

TEST(BadInput, AccessorAndBufferViewRanges) {
  Json count = good_triangle();
  count["accessors"][0]["count"] = 1000000;
  expect_input_error(write_gltf(count), "accessor 0");
  Json offset = good_triangle();
  offset["accessors"][1]["byteOffset"] = 4;
  expect_input_error(write_gltf(offset), "accessor 1");
  Json view = good_triangle();
  view["bufferViews"][0]["byteLength"] = 4000000000u;
  expect_input_error(write_gltf(view));
  Json missing = good_triangle();
  missing["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  expect_input_error(write_gltf(missing));
  Json stride = good_triangle();
  stride["bufferViews"][0]["byteStride"] = 8;  // smaller than a VEC3 of floats
  expect_input_error(write_gltf(stride));
  Json sparse = good_triangle();
  sparse["accessors"][0]["sparse"] = {{"count", 1},
                                      {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
                                      {"values", {{"bufferView", 0}}}};
  expect_input_error(write_gltf(sparse), "sparse");
}

TEST(BadInput, NodeGraph) {
  Json cycle = good_triangle();
  cycle["nodes"] = Json::parse(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])");
  expect_input_error(write_gltf(cycle));
  Json self = good_triangle();
  self["nodes"][0]["children"] = {0};
  expect_input_error(write_gltf(self));
  Json scene = good_triangle();
  scene["scene"] = 3;
  expect_input_error(write_gltf(scene));
}

TEST(BadInput, MissingExternalTexture) {
  Json j = good_triangle();
  j["materials"] =
      Json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  j["textures"] = Json::parse(R"([{"source": 0}])");
  j["images"] = Json::parse(R"([{"uri": "leaf_missing.png"}])");
  j["meshes"][0]["primitives"][0]["material"] = 0;
  expect_input_error(write_gltf(j), "leaf_missing.png");
  j["images"][0]["uri"] = "data:image/png;base64,AAAA";  // not a PNG
  expect_input_error(write_gltf(j), "image 0");
}

TEST(BadInput, DeepJsonAndMissingBuffer) {
  const std::string dir = test::temp_dir("deep");
  test::write_file(dir + "/deep.gltf", R"({"asset": {"version": "2.0"}, "extras": )" +
                                           std::string(100000, '[') + std::string(100000, ']') +
                                           "}");
  expect_input_error(dir + "/deep.gltf", "nested");
  Json j = good_triangle();
  j["buffers"][0]["uri"] = "gone.bin";
  expect_input_error(write_gltf(j), "gone.bin");
}

// External textures next to the .gltf: 16-bit grey and 8-bit RGBA become RGBA8.
TEST(BadInput, ExternalTexturesConverted) {
  Json j = good_triangle();
  j["materials"] =
      Json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])");
  j["textures"] = Json::parse(R"([{"source": 0}])");
  j["meshes"][0]["primitives"][0]["material"] = 0;
  const std::string dir = test::temp_dir("ext");
  cv::Mat grey16(2, 3, CV_16UC1, cv::Scalar(65535));
  grey16.at<uint16_t>(0, 0) = 257 * 10;
  ASSERT_TRUE(cv::imwrite(dir + "/grey16.png", grey16));
  j["images"] = Json::parse(R"([{"uri": "grey16.png"}])");
  test::write_file(dir + "/a.gltf", j.dump());
  Scene s = load_scene(dir + "/a.gltf");
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].width, 3);
  EXPECT_EQ(s.textures[0].rgba[0], 10);
  EXPECT_EQ(s.textures[0].rgba[3], 255);
  EXPECT_EQ(s.textures[0].rgba[4], 255);
  const cv::Mat bgra(2, 2, CV_8UC4, cv::Scalar(30, 60, 100, 7));
  ASSERT_TRUE(cv::imwrite(dir + "/rgba.png", bgra));
  j["images"] = Json::parse(R"([{"uri": "rgba.png"}])");
  test::write_file(dir + "/b.gltf", j.dump());
  Scene t = load_scene(dir + "/b.gltf");
  EXPECT_EQ(t.textures[0].rgba[0], 100);  // BGRA on disk, RGBA in memory
  EXPECT_EQ(t.textures[0].rgba[2], 30);
  EXPECT_EQ(t.textures[0].rgba[3], 7);
}

TEST(BadInput, RequiredExtension) {
  Json j = good_triangle();
  j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  expect_input_error(write_gltf(j), "KHR_draco_mesh_compression");
}

TEST(BadInput, Hierarchy) {
  Json j = good_triangle();
  j["scenes"][0]["extras"]["sylva_hierarchy"] = {
      {"branch_parent", {-1, 0}}, {"branch_diameter", {1.0, 0.5}}, {"leaf_branch", {0, 5}}};
  expect_input_error(write_gltf(j), "leaf_branch");
  j["scenes"][0]["extras"]["sylva_hierarchy"]["leaf_branch"] = {0, 1};
  j["scenes"][0]["extras"]["sylva_hierarchy"]["branch_diameter"] = {1.0};
  expect_input_error(write_gltf(j), "branch_diameter");
  j["scenes"][0]["extras"]["sylva_hierarchy"] = "tree";
  expect_input_error(write_gltf(j), "sylva_hierarchy");
}

TEST(BadInput, DegenerateOnlyScene) {
  static const float p[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0};  // collinear
  static const uint16_t idx[3] = {0, 1, 2};
  expect_input_error(write_gltf(triangle(p, idx)), "degenerate");
}

// Not hostile, but built with the same template: node transforms and primitive modes.
TEST(GltfRead, NodeTransformsMirrorAndModes) {
  Json j = good_triangle();
  j["nodes"] = Json::parse(R"([{"children": [1], "translation": [10, 0, 0],
                                "rotation": [0, 0, 0.70710678, 0.70710678]},
                               {"mesh": 0, "scale": [1, 1, -1]}])");
  Scene s = load_scene(write_gltf(j));
  const Mesh& m = s.meshes[0];
  EXPECT_NEAR(glm::length(m.positions[1] - glm::vec3(10, 1, 0)), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(m.positions[2] - glm::vec3(9, 0, 0)), 0.0f, 1e-5f);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 2, 1}));  // mirrored: winding flipped
  EXPECT_NEAR(m.normals[0].z, -1.0f, 1e-5f);

  const std::vector<float> square = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  Json strip = mesh_gltf(square, {0, 1, 2, 3});
  strip["meshes"][0]["primitives"][0]["mode"] = 5;
  Scene st = load_scene(write_gltf(strip));
  EXPECT_EQ(st.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));  // glTF §3.7.2.1
  Json fan = mesh_gltf(square, {0, 1, 3, 2});
  fan["meshes"][0]["primitives"][0]["mode"] = 6;
  Scene f = load_scene(write_gltf(fan));
  EXPECT_EQ(f.meshes[0].indices, (std::vector<uint32_t>{1, 3, 0, 3, 2, 0}));
  Json points = good_triangle();
  points["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 0}});
  Scene pt = load_scene(write_gltf(points));
  EXPECT_EQ(pt.triangle_count(), 1u);
  EXPECT_FALSE(pt.report.warnings.empty());
  Json unindexed = good_triangle();
  unindexed["meshes"][0]["primitives"][0].erase("indices");
  EXPECT_EQ(load_scene(write_gltf(unindexed)).meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
}

// Every single-byte corruption of a small GLB either loads or is an InputError.
TEST(BadInput, ByteFlipsOfSmallGlb) {
  Scene s;
  Mesh m;
  m.name = "leaf";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = 0;
  s.meshes = {m};
  s.materials.push_back(Material{"leaf", glm::vec4(1), 0, AlphaMode::Mask, 0.5f, true});
  s.textures.push_back(Texture{"t", 2, 2, std::vector<uint8_t>(16, 200)});
  finish_scene(s, {});
  const std::string dir = test::temp_dir("flip");
  write_glb(s, dir + "/ok.glb");
  const std::string bytes = test::read_file(dir + "/ok.glb");
  size_t errors = 0;
  for (size_t at = 0; at < bytes.size(); at += 5) {
    for (uint8_t x : {uint8_t(0xff), uint8_t(0x01)}) {
      std::string bad = bytes;
      bad[at] = char(uint8_t(bad[at]) ^ x);
      const std::string path = dir + "/flip.glb";
      test::write_file(path, bad);
      try {
        load_scene(path);
      } catch (const InputError&) {
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 0u);
}

// Found by the fuzzer in OpenMesh's readers (tests/fuzz/regressions/), which Sylva's own readers
// replaced: a PLY header line OpenMesh looped forever on, an OBJ face with a bad vertex index
// and texture coordinates (OpenMesh wrote past its arrays), OFF colours far outside [0, 1]
// (OpenMesh cast them out of range), an OFF face claiming 2^31 vertices (OpenMesh grew a 2 GiB
// vector), an OBJ face whose vertices are all bad (OpenMesh asserted).
TEST(BadInput, HostileMeshFilesFoundByTheFuzzer) {
  const std::string dir = test::temp_dir("openmesh-fuzz");
  test::write_file(dir + "/header.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "prproperty float z\nproperty uindices\nend_header\n1 2\n");
  expect_input_error(dir + "/header.ply", "line 6: not a PLY header line: 'prproperty'");
  test::write_file(dir + "/texcoord.obj",
                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                   "f 1/1 2/2 3/3\nf 1/1 2/2 7/3\n");
  expect_input_error(dir + "/texcoord.obj", "line 8: expected a vertex index (1 to 3,");
  test::write_file(dir + "/colour.off",
                   "COFF\n3 1 0\n0 0 0 -25.9 1e30 0.5\n1 0 0 0.5 0.5 0.5\n"
                   "0 1 0 0.2 0.3 0.4\n3 0 1 2\n");
  const Scene off = load_scene(dir + "/colour.off");
  for (const glm::vec4& c : off.meshes[0].colors)
    for (int k = 0; k < 4; ++k)
      EXPECT_TRUE(c[k] >= 0.0f && c[k] <= 1.0f) << c[k];
  test::write_file(dir + "/count.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2147483647 0 1 2\n");
  expect_input_error(dir + "/count.off", "line 6: expected a face's vertex count");
  test::write_file(dir + "/allbad.obj", "v 0 0 0\nf 0 -7 x\nf 5 6 7\n");
  expect_input_error(dir + "/allbad.obj", "");
}

// A reader's complaints come out only in the one error line, or as one warning of a scene that
// loads (OpenMesh's readers printed them to std::cerr and std::clog).
TEST(BadInput, ReaderMessagesGoIntoTheErrorOrAWarning) {
  const std::string dir = test::temp_dir("reader-messages");
  test::write_file(dir + "/dim.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n");
  test::write_file(dir + "/index.obj", "v 1 2 3\nf 1 2 9\n");
  // OBJ faces name what came before them or are an error; OFF faces out of range are skipped.
  test::write_file(dir + "/some.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 9\n");
  testing::internal::CaptureStderr();
  expect_input_error(dir + "/dim.ply", "the vertex element has no x, y and z properties");
  expect_input_error(dir + "/index.obj",
                     "line 2: expected a vertex index (1 to 1, or -1 to -1 counting back from the "
                     "last 'v'), got '2'");
  const Scene scene = load_scene(dir + "/some.off");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(scene.report.warnings.size(), 1u) << scene.report.warnings[1];
  EXPECT_NE(scene.report.warnings[0].find(
                "skipped 1 face(s) that cannot be drawn, the first at line 7: the face has vertex "
                "index 9 out of range (3 vertices)"),
            std::string::npos)
      << scene.report.warnings[0];
  EXPECT_EQ(scene.triangle_count(), 1u);
}

}  // namespace
}  // namespace sylva
