// The hostile-input suite, generated at test time: every parameter of every built-in style at
// NaN, ±inf, ±1e308, empty and text, and byte flips, truncations and JSON edits of the samples
// and of the shared trees. Each run must exit 0, or exit 2 with exactly one `sylva: error:` line
// (the last; information lines may precede it) and leave no file behind; none may run over
// 20 s or 2 GiB of address space (`timeout` and `ulimit -v` in the run's script). Runs go two at
// a time (xargs -P 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "tests/cli/cli_support.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

namespace fs = std::filesystem;

struct Case {
  std::string args;    // after "sylva"; OUT stands for the case's output file
  std::string output;  // the output's name in the case folder ("" = none)
};

struct Outcome {
  int status = -1;
  std::string err;
  bool output_left = false;
  std::vector<std::string> files;  // everything in the case folder but the run's own logs
};

// Runs every case in its own folder, two at a time; returns the outcomes in order.
std::vector<Outcome> run_cases(const std::vector<Case>& cases, const std::string& tag) {
  const std::string root = temp_dir(tag);
  std::ostringstream list;
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string dir = root + "/" + std::to_string(i);
    fs::create_directory(dir);
    std::string args = cases[i].args;
    const size_t out = args.find("OUT");
    if (out != std::string::npos) args.replace(out, 3, dir + "/" + cases[i].output);
    write_file(dir + "/run.sh", "cd " + dir + " && ulimit -v 2097152 && timeout 20 " +
                                    sylva_binary() + " " + args +
                                    " > .stdout 2> .stderr; echo $? > .status\n");
    list << dir << "/run.sh\n";
  }
  write_file(root + "/list", list.str());
  const RunResult r = run_sylva("--version > /dev/null && xargs -P 2 -n 1 sh < " + root + "/list");
  EXPECT_EQ(r.status, 0) << r.output;
  std::vector<Outcome> outcomes;
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string dir = root + "/" + std::to_string(i);
    Outcome o;
    o.status = std::stoi(read_file(dir + "/.status"));
    o.err = read_file(dir + "/.stderr");
    for (const std::string& name : listing(dir))
      if (!name.starts_with(".") || name.find(".tmp") != std::string::npos)
        if (name != "run.sh") o.files.push_back(name);
    o.output_left = !cases[i].output.empty() && file_exists(dir + "/" + cases[i].output);
    outcomes.push_back(o);
    fs::remove_all(dir);
  }
  return outcomes;
}

// Exit 0 (and the output, if any, written), or exit 2 with one error line, the last, and
// nothing left in the folder.
void expect_clean(const Case& c, const Outcome& o) {
  const std::string what = c.args + "\n" + o.err;
  ASSERT_TRUE(o.status == 0 || o.status == 2) << "status " << o.status << ": " << what;
  if (o.status == 0) {
    if (!c.output.empty()) {
      EXPECT_TRUE(o.output_left) << what;
    }
    return;
  }
  int errors = 0;
  std::istringstream lines(o.err);
  std::string line, last;
  for (; std::getline(lines, line); last = line)
    errors += line.starts_with("sylva: error: ") ? 1 : 0;
  EXPECT_EQ(errors, 1) << what;
  EXPECT_TRUE(last.starts_with("sylva: error: ")) << what;
  EXPECT_EQ(o.files, std::vector<std::string>{}) << what;
}

// Every key `sylva styles NAME` lists, with the first built-in style that has it.
std::map<std::string, std::string> style_keys() {
  std::map<std::string, std::string> keys;
  for (const char* style :
       {"standard", "expressive", "ink", "pen", "toon", "watercolor", "blobs"}) {
    const RunResult r = run_sylva(std::string("styles ") + style);
    EXPECT_EQ(r.status, 0) << r.output;
    std::istringstream lines(r.output);
    bool table = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.starts_with("key ")) {
        table = true;
        continue;
      }
      const std::string key = line.substr(0, line.find(' '));
      if (table && key.find('.') != std::string::npos) keys.emplace(key, style);
    }
  }
  return keys;
}

TEST(Hostile, EveryStyleKeyAtHostileValues) {
  const std::map<std::string, std::string> keys = style_keys();
  ASSERT_GT(keys.size(), 100u);
  std::vector<Case> cases;
  for (const auto& [key, style] : keys)
    for (const char* value : {"nan", "inf", "-inf", "1e308", "-1e308", "", "text"})
      cases.push_back({"render " + small_tree() + " --style " + style + " --size 32 --set '" + key +
                           "=" + value + "' -o OUT",
                       "out.png"});
  const std::vector<Outcome> outcomes = run_cases(cases, "hostile-keys");
  int refused = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    expect_clean(cases[i], outcomes[i]);
    refused += outcomes[i].status == 2 ? 1 : 0;
  }
  EXPECT_GT(refused, int(cases.size()) / 2);  // nan, inf, empty and text are refused nearly always
}

std::vector<std::string> scenes() {
  std::vector<std::string> paths = {small_tree(), sampled_scene("hostile-bush", "bush --seed 2")};
  for (const auto& e : fs::directory_iterator(shared_dir() + "/assets"))
    if (e.path().extension() == ".glb") paths.push_back(e.path().string());
  std::sort(paths.begin() + 2, paths.end());
  return paths;
}

// Seeded mutations of a .glb: truncations, byte flips in the JSON and in the binary chunk.
std::vector<std::string> mutations(const std::string& bytes, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::string> out;
  for (double f : {0.0, 0.01, 0.05, 0.3, 0.5, 0.9, 0.999})
    out.push_back(bytes.substr(0, size_t(double(bytes.size()) * f)));
  const size_t json_end = std::min<size_t>(
      bytes.size(), 20 + (uint8_t(bytes[12]) | uint8_t(bytes[13]) << 8 | uint8_t(bytes[14]) << 16));
  for (int i = 0; i < 10; ++i) {
    std::string m = bytes;
    const bool in_json = i < 6;
    std::uniform_int_distribution<size_t> at(in_json ? 20 : json_end,
                                             (in_json ? json_end : bytes.size()) - 1);
    for (int k = 0; k < 1 + i % 3; ++k)
      m[at(rng)] = char(rng());
    out.push_back(m);
  }
  return out;
}

// JSON edits a hostile file makes: huge or negative counts, offsets and strides, out-of-range
// views, wrong component types, bad indices, cyclic nodes, bogus image URIs.
std::vector<std::string> json_edits(const std::string& glb) {
  const uint32_t len = uint8_t(glb[12]) | uint8_t(glb[13]) << 8 | uint8_t(glb[14]) << 16 |
                       uint32_t(uint8_t(glb[15])) << 24;
  const nlohmann::json base = nlohmann::json::parse(glb.substr(20, len));
  const std::string rest = glb.substr(20 + len);
  std::vector<nlohmann::json> edits;
  auto edit = [&](const std::function<void(nlohmann::json&)>& f) {
    nlohmann::json j = base;
    f(j);
    edits.push_back(j);
  };
  edit([](auto& j) { j["accessors"][0]["count"] = 4294967295.0; });
  edit([](auto& j) { j["accessors"][0]["count"] = -5; });
  edit([](auto& j) { j["accessors"][0]["byteOffset"] = 1e18; });
  edit([](auto& j) { j["accessors"][0]["componentType"] = 5130; });
  edit([](auto& j) { j["accessors"][0]["type"] = "MAT4"; });
  edit([](auto& j) { j["bufferViews"][0]["byteStride"] = 252; });
  edit([](auto& j) { j["bufferViews"][0]["byteLength"] = 1e15; });
  edit([](auto& j) { j["bufferViews"][0]["buffer"] = 99; });
  edit([](auto& j) { j["meshes"][0]["primitives"][0]["indices"] = 1 << 30; });
  edit([](auto& j) { j["nodes"][0]["children"] = {0}; });
  edit([](auto& j) { j["scenes"][0]["nodes"] = {-1}; });
  edit([](auto& j) {
    if (j.contains("images")) j["images"][0] = {{"uri", "data:image/png;base64,!!!!"}};
  });
  edit([](auto& j) { j["extensionsRequired"] = {"KHR_draco_mesh_compression"}; });
  std::vector<std::string> out;
  for (const nlohmann::json& j : edits) {
    std::string text = j.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    std::string m = glb.substr(0, 12);
    const uint32_t total = uint32_t(12 + 8 + text.size() + rest.size());
    for (int b = 0; b < 4; ++b)
      m[8 + b] = char(total >> (8 * b));
    for (int b = 0; b < 4; ++b)
      m += char(uint32_t(text.size()) >> (8 * b));
    m += "JSON" + text + rest;
    out.push_back(m);
  }
  return out;
}

TEST(Hostile, MutatedScenesLoadOrFailInOneLine) {
  const std::string dir = temp_dir("hostile-scenes");
  std::vector<Case> cases;
  int n = 0;
  for (const std::string& scene : scenes()) {
    const std::string bytes = read_file(scene);
    std::vector<std::string> all = mutations(bytes, uint32_t(n + 1));
    for (std::string& m : json_edits(bytes))
      all.push_back(std::move(m));
    for (const std::string& m : all) {
      const std::string path = dir + "/m" + std::to_string(n++) + ".glb";
      write_file(path, m);
      cases.push_back({"info " + path, ""});
      if (n % 4 == 0)  // and a render of some, which reads every texture too
        cases.push_back({"render " + path + " --size 32 -o OUT", "out.png"});
    }
  }
  const std::vector<Outcome> outcomes = run_cases(cases, "hostile-runs");
  int refused = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    expect_clean(cases[i], outcomes[i]);
    refused += outcomes[i].status == 2 ? 1 : 0;
  }
  EXPECT_GT(refused, int(cases.size()) / 4);                       // most mutations are refused ...
  EXPECT_GT(int(cases.size()) - refused, int(cases.size()) / 20);  // ... and some still load
}

// Hostile OBJ and PLY text: huge counts, NaN coordinates, indices out of range, binary junk.
TEST(Hostile, HostileObjAndPly) {
  const std::string dir = temp_dir("hostile-mesh");
  const std::vector<std::pair<std::string, std::string>> files = {
      {"nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"inf.obj", "v 1e39 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"},
      {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n"},
      {"negative.obj", "v 0 0 0\nf -5 -6 -7\n"},
      {"junk.obj", std::string("v \x01\xff\x00 3\nf a b c\n", 20)},
      {"empty.obj", ""},
      {"count.ply",
       "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
       "property float y\nproperty float z\nend_header\n0 0 0\n"},
      {"negative.ply", "ply\nformat ascii 1.0\nelement vertex -3\nproperty float x\nend_header\n"},
      {"face.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
       "end_header\n0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n"},
      {"binary.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 1000000\n"
       "property float x\nend_header\n\x01\x02"},
  };
  std::vector<Case> cases;
  for (const auto& [name, text] : files) {
    write_file(dir + "/" + name, text);
    cases.push_back({"info " + dir + "/" + name, ""});
    cases.push_back({"render " + dir + "/" + name + " --size 32 -o OUT", "out.png"});
  }
  const std::vector<Outcome> outcomes = run_cases(cases, "hostile-mesh-runs");
  for (size_t i = 0; i < cases.size(); ++i)
    expect_clean(cases[i], outcomes[i]);
}

}  // namespace
}  // namespace sylva::test
