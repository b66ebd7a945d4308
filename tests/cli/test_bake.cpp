// sylva bake: the written .glb is valid glTF (Khronos validator), carries unit realigned
// normals and ka as _AMBIENT and COLOR_0, reads back into Mesh::ka, is byte-deterministic,
// renders, and bad input writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/scene/load.h"
#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

using Json = nlohmann::json;

constexpr float kKaMin = 0.3f;

// A small sample tree, generated once per test program.
const std::string& tree() {
  static const std::string path = [] {
    const std::string p = temp_dir("bake-tree") + "/t.glb";
    const RunResult r = run_sylva("sample tree --leaves 2000 --seed 3 -o " + p);
    EXPECT_EQ(r.status, 0) << r.output;
    return p;
  }();
  return path;
}

RunResult bake(const std::string& scene, const std::string& out) {
  return run_sylva("bake " + scene + " --ka-min 0.3 -o " + out);
}

// Bakes once; the summary line and "wrote" are reported.
std::string bake_once(const std::string& scene, const std::string& name) {
  const std::string p = temp_dir("bake") + "/" + name + ".glb";
  const RunResult r = bake(scene, p);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("foliage illumination: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("wrote " + p), std::string::npos) << r.output;
  return p;
}

const std::string& baked_tree() {
  static const std::string path = bake_once(tree(), "tree");
  return path;
}

const std::string& baked_fern() {
  static const std::string path = bake_once(fern_path(), "fern");
  return path;
}

// The JSON chunk and the BIN chunk of a .glb.
struct Glb {
  Json json;
  std::string bin;
};

Glb parse_glb(const std::string& bytes) {
  Glb g;
  uint32_t json_len = 0, bin_len = 0;
  std::memcpy(&json_len, bytes.data() + 12, 4);
  g.json = Json::parse(bytes.substr(20, json_len));
  std::memcpy(&bin_len, bytes.data() + 20 + json_len, 4);
  g.bin = bytes.substr(20 + json_len + 8, bin_len);
  return g;
}

// A float accessor as Sylva writes it (tightly packed); `comps` receives the component count.
std::vector<float> floats(const Glb& g, size_t accessor, int& comps) {
  const Json& a = g.json["accessors"][accessor];
  EXPECT_EQ(a["componentType"], 5126);
  const std::string type = a["type"];
  comps = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
  const Json& view = g.json["bufferViews"][a["bufferView"].get<size_t>()];
  std::vector<float> out(a["count"].get<size_t>() * size_t(comps));
  std::memcpy(out.data(), g.bin.data() + view["byteOffset"].get<size_t>(), out.size() * 4);
  return out;
}

// In the file: NORMAL unit and finite, _AMBIENT in [ka_min, 1], COLOR_0 = (ka, ka, ka).
void check_file(const std::string& path) {
  const Glb g = parse_glb(read_file(path));
  EXPECT_EQ(g.json["scenes"][0]["extras"]["sylva_baked"]["ka_min"].get<double>(), 0.3);
  ASSERT_TRUE(g.json.contains("meshes"));
  for (const Json& mesh : g.json["meshes"]) {
    const Json& at = mesh["primitives"][0]["attributes"];
    ASSERT_TRUE(at.contains("NORMAL") && at.contains("_AMBIENT") && at.contains("COLOR_0"))
        << at.dump();
    int nc = 0, kc = 0, cc = 0;
    const std::vector<float> n = floats(g, at["NORMAL"], nc);
    const std::vector<float> ka = floats(g, at["_AMBIENT"], kc);
    const std::vector<float> color = floats(g, at["COLOR_0"], cc);
    ASSERT_EQ(nc, 3);
    ASSERT_EQ(kc, 1);
    ASSERT_EQ(cc, 3);
    ASSERT_EQ(n.size(), 3 * ka.size());
    ASSERT_EQ(color.size(), 3 * ka.size());
    size_t bad_normals = 0, bad_ka = 0, bad_color = 0;
    for (size_t v = 0; v < ka.size(); ++v) {
      const float len = std::sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] +
                                  n[3 * v + 2] * n[3 * v + 2]);
      bad_normals += !(std::abs(len - 1.0f) < 1e-3f);  // also catches NaN
      bad_ka += !(ka[v] >= kKaMin && ka[v] <= 1.0f);
      for (int c = 0; c < 3; ++c)
        bad_color += color[3 * v + size_t(c)] != ka[v];
    }
    EXPECT_EQ(bad_normals, 0u) << mesh["name"];
    EXPECT_EQ(bad_ka, 0u) << mesh["name"];
    EXPECT_EQ(bad_color, 0u) << mesh["name"];
  }
}

// Through the library loader: Mesh::ka read from _AMBIENT, in [ka_min, 1], varying on foliage;
// the normals are marked outward.
void check_loaded(const std::string& path) {
  const Scene s = load_scene(path);
  float lo = 1.0f, hi = 0.0f;
  for (const Mesh& m : s.meshes) {
    ASSERT_EQ(m.ka.size(), m.positions.size()) << m.name;
    EXPECT_TRUE(m.outward_normals) << m.name;  // back faces keep the realigned normals
    for (float k : m.ka) {
      EXPECT_GE(k, kKaMin);
      EXPECT_LE(k, 1.0f);
    }
    for (const glm::vec3& n : m.normals)
      EXPECT_NEAR(glm::length(n), 1.0f, 1e-3f);
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (m.roles[t] == Role::Foliage)
        for (int c = 0; c < 3; ++c) {
          lo = std::min(lo, m.ka[m.indices[3 * t + size_t(c)]]);
          hi = std::max(hi, m.ka[m.indices[3 * t + size_t(c)]]);
        }
  }
  EXPECT_GT(hi - lo, 0.2f) << "foliage ka in [" << lo << ", " << hi << "]";
}

void expect_valid_gltf(const std::string& path) {
  ASSERT_TRUE(gltf_validator_installed()) << "run scripts/setup.sh (npm install of gltf-validator)";
  const RunResult v = validate_gltf(path);
  EXPECT_EQ(v.status, 0) << v.output;
  EXPECT_NE(v.output.find("errors=0"), std::string::npos) << v.output;
}

TEST(Bake, SampleTree) {
  expect_valid_gltf(baked_tree());
  check_file(baked_tree());
  check_loaded(baked_tree());
}

TEST(Bake, Fern) {
  expect_valid_gltf(baked_fern());
  check_file(baked_fern());
  check_loaded(baked_fern());
}

TEST(Bake, SameInputsSameBytes) {
  const std::string again = temp_dir("bake-again") + "/tree.glb";
  ASSERT_EQ(bake(tree(), again).status, 0);
  EXPECT_TRUE(read_file(again) == read_file(baked_tree()));
}

TEST(Bake, RenderDrawsTheBakedFile) {
  const std::string png = temp_dir("bake-render") + "/x.png";
  const RunResult r = run_sylva("render " + baked_tree() + " --size 96 -o " + png);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(file_exists(png));
}

TEST(Bake, BadInputWritesNothing) {
  const std::string dir = temp_dir("bake-bad");
  const std::string out = dir + "/out.glb";
  const std::pair<std::string, std::string> cases[] = {
      {"bake " + tree() + " --ka-min 1.5 -o " + out, "--ka-min"},
      {"bake " + tree() + " --grid 1 -o " + out, "--grid"},
      {"bake " + tree() + " -o " + dir + "/out.png", "--output"},
      {"bake " + dir + "/missing.glb -o " + out, "missing.glb"},
      {"bake " + tree() + " --ka-encoding attribute -o " + out, "--ka-encoding"},
      {"bake " + tree() + " --surface-out " + out + " -o " + out, "--surface-out"},
  };
  for (const auto& [args, needle] : cases) {
    expect_input_error(args, needle);
    EXPECT_FALSE(file_exists(out)) << args;
    EXPECT_FALSE(file_exists(dir + "/out.png")) << args;
  }
}

}  // namespace
}  // namespace sylva::test
