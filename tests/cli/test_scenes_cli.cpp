// Scenes of many plants from the command line: `sample park` (counts, determinism, ranges),
// an instanced park against its flattened twin, `bake` keeping the instancing with each
// plant's ka as the lone plant's, EXT_mesh_gpu_instancing files, and cameras from the file
// (`--camera`, camera.json, turntable, `info`).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/glm.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <tuple>

#include "core/scene/gltf_write.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "tests/cli/cli_support.h"
#include "tests/core/scene/gltf_builder.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

using Json = nlohmann::json;

const std::string& lone_tree() {
  return sampled_scene("park-tree", "tree --seed 2 --leaves 1500");
}

// A park of 12 instances of the lone tree, made once.
const std::string& park() {
  static const std::string path = [] {
    const std::string p = temp_dir("park") + "/park.glb";
    const RunResult r = run_sylva("sample park --plants " + lone_tree() +
                                  " --count 12 --area 40x30 --seed 5 -o " + p);
    EXPECT_EQ(r.status, 0) << r.output;
    return p;
  }();
  return path;
}

Json info_json(const std::string& scene) {
  const RunResult r = run_sylva("info --json " + scene);
  EXPECT_EQ(r.status, 0) << r.output;
  return Json::parse(r.output, nullptr, false);
}

// The glTF JSON chunk of a .glb.
Json glb_json(const std::string& path) {
  const std::string bytes = read_file(path);
  uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  return Json::parse(bytes.substr(20, length));
}

TEST(Park, InfoCountsInstancesPlantsAndTriangles) {
  const Json lone = info_json(lone_tree());
  const Json j = info_json(park());
  EXPECT_EQ(j["instances"], 12);
  EXPECT_EQ(j["plants"], 1);
  EXPECT_EQ(j["distinct_triangles"], lone["triangles"]);
  EXPECT_EQ(j["triangles"], 12 * lone["triangles"].get<size_t>());
  EXPECT_EQ(j["leaves"], lone["leaves"]);
  EXPECT_EQ(j["cameras"].size(), 2u);
  const RunResult text = run_sylva("info " + park());
  EXPECT_NE(text.output.find("plants      1 distinct, 12 instances"), std::string::npos)
      << text.output;
}

TEST(Park, SameSeedSameBytesOtherSeedOtherLayout) {
  const std::string dir = temp_dir("park-seed");
  for (const char* name : {"a", "b"})
    ASSERT_EQ(run_sylva("sample park --plants " + lone_tree() +
                        " --count 7 --area 20 --seed 9 -o " + dir + "/" + name + ".glb")
                  .status,
              0);
  ASSERT_EQ(run_sylva("sample park --plants " + lone_tree() + " --count 7 --area 20 --seed 10 -o " +
                      dir + "/c.glb")
                .status,
            0);
  EXPECT_EQ(read_file(dir + "/a.glb"), read_file(dir + "/b.glb"));
  EXPECT_NE(read_file(dir + "/a.glb"), read_file(dir + "/c.glb"));
  const Scene s = load_scene(dir + "/a.glb");
  EXPECT_EQ(s.instance_count(), 7u);
  const Bounds b = s.bounds();  // the instances stand inside the 20 x 20 area
  const Bounds plant = load_scene(lone_tree()).bounds();
  const float reach = 1.2f * std::max({std::abs(plant.min.x), std::abs(plant.max.x),
                                       std::abs(plant.min.z), std::abs(plant.max.z)});
  EXPECT_GE(b.min.x, -10.0f - reach);
  EXPECT_LE(b.max.z, 10.0f + reach);
}

TEST(Park, OptionsOutOfRangeAreOneLineErrors) {
  const std::string dir = temp_dir("park-bad");
  const std::string base = "sample park --plants " + lone_tree() + " -o " + dir + "/p.glb ";
  expect_input_error(base + "--count 0", "--count");
  expect_input_error(base + "--count 100001", "--count");
  expect_input_error(base + "--count -3", "--count");
  expect_input_error(base + "--area 0x5", "--area");
  expect_input_error(base + "--area 10x1000001", "--area");
  expect_input_error(base + "--area -4", "--area");
  expect_input_error(base + "--area 10xabc", "--area");
  expect_input_error("sample park -o " + dir + "/p.glb", "--plants");
  expect_input_error("sample park --plants " + dir + "/missing.glb -o " + dir + "/p.glb",
                     "missing.glb");
  expect_input_error("sample tree --count 5 -o " + dir + "/p.glb", "--count");
  expect_input_error("sample park --leaves 500 --plants " + lone_tree() + " -o " + dir + "/p.glb",
                     "--leaves");
  EXPECT_FALSE(file_exists(dir + "/p.glb"));
  // The ends of the ranges are accepted.
  EXPECT_EQ(run_sylva(base + "--count 1 --area 1000000x0.001").status, 0);
}

// The park flattened into one world-space mesh per instance, as a file of its own.
const std::string& flattened_park() {
  static const std::string path = [] {
    const std::string p = temp_dir("park-flat") + "/flat.glb";
    const Scene flat = flatten(load_scene(park()));
    EXPECT_FALSE(flat.instanced());
    write_glb(flat, p);
    return p;
  }();
  return path;
}

// The share of pixels differing by more than 24 levels in a channel (the golden tolerance).
double failing_share(const std::string& a, const std::string& b) {
  const cv::Mat x = cv::imread(a, cv::IMREAD_UNCHANGED), y = cv::imread(b, cv::IMREAD_UNCHANGED);
  EXPECT_EQ(x.size(), y.size());
  if (x.size() != y.size() || x.empty()) return 1.0;
  cv::Mat d;
  cv::absdiff(x, y, d);
  d = d.reshape(1, int(d.total()));
  cv::reduce(d, d, 1, cv::REDUCE_MAX);
  return double(cv::countNonZero(d > 24)) / double(d.total());
}

TEST(Park, RendersTheSamePixelsAsItsFlattenedTwin) {
  const std::string dir = temp_dir("park-twin");
  EXPECT_EQ(info_json(flattened_park())["instances"], 1);
  // Styles by leaf cluster (pen's regions, watercolor's washes, blobs) are not compared: the
  // park's clusters are made per plant, the twin's over the whole scene; ink outlines each plant
  // of the park, which the twin has not (below).
  for (const char* style : {"standard", "toon"}) {
    for (const std::string& scene : {park(), flattened_park()}) {
      const std::string out = dir + "/" + style + (scene == park() ? "-park.png" : "-flat.png");
      const RunResult r = run_sylva("render " + scene + " --style " + style +
                                    " --size 320x240 --lod off -o " + out);
      ASSERT_EQ(r.status, 0) << r.output;
    }
    EXPECT_LE(failing_share(dir + "/" + style + "-park.png", dir + "/" + style + "-flat.png"), 0.01)
        << style;
  }
}

// Line pixels (grey below 128) of `a` farther than `px` from every line pixel of `b`, as a share
// of a's line pixels; the count of a's line pixels in `lines`.
double lines_away_from(const std::string& a, const std::string& b, float px, int& lines) {
  const cv::Mat x = cv::imread(a, cv::IMREAD_GRAYSCALE), y = cv::imread(b, cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(x.size(), y.size());
  lines = 0;
  if (x.size() != y.size() || x.empty()) return 1.0;
  cv::Mat distance;
  cv::distanceTransform(y >= 128, distance, cv::DIST_L2, 3);
  int away = 0;
  for (int r = 0; r < x.rows; ++r)
    for (int c = 0; c < x.cols; ++c)
      if (x.at<uint8_t>(r, c) < 128) {
        ++lines;
        away += distance.at<float>(r, c) > px;
      }
  return lines ? double(away) / double(lines) : 1.0;
}

// The outline drawing (the `outline` preset, lines.plants) draws the park's outline where its
// flattened twin draws it (the same surface points, each instance's placed by its transform:
// npr/surface_samples.h), and inside it each plant's outline where its crown stands in front of
// another's, which the twin (one plant) has not.
TEST(Park, InkOutlinesTheParkAsItsTwinAndEachPlantInIt) {
  const std::string dir = temp_dir("park-ink");
  for (const std::string& scene : {park(), flattened_park()}) {
    const std::string out = dir + (scene == park() ? "/park.png" : "/flat.png");
    const RunResult r =
        run_sylva("render " + scene + " --style outline --size 640x480 --lod off -o " + out);
    ASSERT_EQ(r.status, 0) << r.output;
  }
  int twin_lines = 0, park_lines = 0;
  EXPECT_LE(lines_away_from(dir + "/flat.png", dir + "/park.png", 1.5f, twin_lines), 0.01);
  const double inside = lines_away_from(dir + "/park.png", dir + "/flat.png", 2.5f, park_lines);
  std::printf("twin %d line px, park %d, %.3f of the park's away from the twin's lines\n",
              twin_lines, park_lines, inside);
  EXPECT_GT(inside, 0.08);  // the plants' own outlines (15 % here)
  // Without them (lines.plants = false) the park draws its twin's lines.
  const RunResult r =
      run_sylva("render " + park() +
                " --style outline --set lines.plants=false --size 640x480 --lod off "
                "-o " +
                dir + "/without.png");
  ASSERT_EQ(r.status, 0) << r.output;
  int without_lines = 0;
  EXPECT_LE(lines_away_from(dir + "/without.png", dir + "/flat.png", 1.5f, without_lines), 0.01);
}

// The look at the scale of `block` px: of the block x block squares a plant touches in either
// image (any pixel with a channel below 250), the share whose mean colour differs by more than
// 24 levels in a channel.
double changed_block_share(const std::string& a, const std::string& b, int block) {
  const cv::Mat x = cv::imread(a, cv::IMREAD_COLOR), y = cv::imread(b, cv::IMREAD_COLOR);
  EXPECT_EQ(x.size(), y.size());
  if (x.size() != y.size() || x.empty()) return 1.0;
  cv::Mat channels[3], small_x, small_y, small_cover;
  cv::split(cv::min(x, y), channels);
  const cv::Mat cover = cv::min(cv::min(channels[0], channels[1]), channels[2]) < 250;
  const cv::Size small(x.cols / block, x.rows / block);
  cv::resize(x, small_x, small, 0, 0, cv::INTER_AREA);
  cv::resize(y, small_y, small, 0, 0, cv::INTER_AREA);
  cv::resize(cover, small_cover, small, 0, 0, cv::INTER_AREA);  // > 0: touched
  size_t covered = 0, changed = 0;
  for (int r = 0; r < small_x.rows; ++r)
    for (int c = 0; c < small_x.cols; ++c) {
      if (!small_cover.at<uint8_t>(r, c)) continue;
      const cv::Vec3b p = small_x.at<cv::Vec3b>(r, c), q = small_y.at<cv::Vec3b>(r, c);
      bool differ = false;
      for (int k = 0; k < 3; ++k)
        differ = differ || std::abs(int(p[k]) - int(q[k])) > 24;
      ++covered;
      changed += differ;
    }
  return covered ? double(changed) / double(covered) : 1.0;
}

// Line drawings: the share of line pixels (grey below 128) of either image farther than 3 px
// from every line pixel of the other.
double moved_line_share(const std::string& a, const std::string& b) {
  const cv::Mat x = cv::imread(a, cv::IMREAD_GRAYSCALE), y = cv::imread(b, cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(x.size(), y.size());
  if (x.size() != y.size() || x.empty()) return 1.0;
  size_t lines = 0, moved = 0;
  for (const auto& [from, to] : {std::pair{x, y}, std::pair{y, x}}) {
    cv::Mat distance;
    cv::distanceTransform(to >= 128, distance, cv::DIST_L2, 3);  // to the nearest line pixel
    for (int r = 0; r < from.rows; ++r)
      for (int c = 0; c < from.cols; ++c)
        if (from.at<uint8_t>(r, c) < 128) {
          ++lines;
          moved += distance.at<float>(r, c) > 3.0f;
        }
  }
  return lines ? double(moved) / double(lines) : 1.0;
}

// Distant plants (about 60 to 100 px tall at 640 x 480) drawn at their levels of detail against
// drawn whole: the bounds the README states (Scenes of many plants).
TEST(Lod, DistantPlantsChangeLittle) {
  const std::string dir = temp_dir("lod");
  for (const char* style : {"standard", "ink"}) {
    for (const char* lod : {"on", "off"}) {
      const RunResult r = run_sylva("render " + park() + " --style " + style + " --lod " + lod +
                                    " --size 640x480 -o " + dir + "/" + style + "-" + lod + ".png");
      ASSERT_EQ(r.status, 0) << r.output;
    }
    const std::string on = dir + "/" + style + "-on.png", off = dir + "/" + style + "-off.png";
    const bool ink = std::string(style) == "ink";
    const double share = ink ? moved_line_share(on, off) : changed_block_share(on, off, 16);
    std::printf("%s: %.4f\n", style, share);
    EXPECT_LE(share, 0.05) << style;
    // ink's outline is the scene's surface samples projected (npr/surface_samples.h), not the
    // drawn triangles, and the distant trees' wood lines are below its minimum length: the
    // levels leave it unchanged, which is what this bound asks for.
    if (!ink) {
      EXPECT_NE(read_file(on), read_file(off)) << style << ": the levels of detail were not used";
    }
  }
  expect_input_error("render " + park() + " --lod maybe --size 64 -o " + dir + "/x.png", "--lod");
}

// The ka of every vertex of `a` against `b`'s same mesh: root mean square difference.
double ka_rmse(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.ka.size(), b.ka.size());
  double sum = 0.0;
  for (size_t v = 0; v < a.ka.size() && v < b.ka.size(); ++v)
    sum += double(a.ka[v] - b.ka[v]) * double(a.ka[v] - b.ka[v]);
  return a.ka.empty() ? 1.0 : std::sqrt(sum / double(a.ka.size()));
}

TEST(Park, BakeKeepsTheInstancingAndEachPlantsKaIsTheLonePlants) {
  const std::string dir = temp_dir("park-bake");
  ASSERT_EQ(run_sylva("bake " + lone_tree() + " --no-cache -o " + dir + "/lone.glb").status, 0);
  const RunResult r = run_sylva("bake " + park() + " --no-cache -o " + dir + "/park.glb");
  ASSERT_EQ(r.status, 0) << r.output;
  const Scene lone = load_scene(dir + "/lone.glb");
  const Scene baked = load_scene(dir + "/park.glb");
  ASSERT_TRUE(baked.instanced());
  EXPECT_EQ(baked.instance_count(), 12u);
  EXPECT_EQ(glb_json(dir + "/park.glb")["meshes"].size(),
            glb_json(dir + "/lone.glb")["meshes"].size());
  ASSERT_EQ(baked.meshes.size(), lone.meshes.size());
  const Json note = glb_json(dir + "/park.glb")["scenes"][0]["extras"]["sylva_baked"];
  ASSERT_EQ(note["plants"].size(), 1u);
  EXPECT_EQ(note["plants"][0]["rho"], note["rho"]);
  for (size_t m = 0; m < lone.meshes.size(); ++m) {
    EXPECT_EQ(baked.meshes[m].name, lone.meshes[m].name);
    EXPECT_LE(ka_rmse(baked.meshes[m], lone.meshes[m]), 0.01) << lone.meshes[m].name;
  }
}

TEST(Park, TheImplicitSurfacesArePlacedByTheInstances) {
  const std::string dir = temp_dir("park-surface");
  const RunResult r = run_sylva("render " + park() + " --style expressive --size 64 --no-cache " +
                                "--surface-out " + dir + "/s.glb -o " + dir + "/e.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const Scene s = load_scene(dir + "/s.glb");
  ASSERT_TRUE(s.instanced());
  EXPECT_EQ(s.plant_count(), 1u);
  EXPECT_EQ(s.instance_count(), 12u);
  EXPECT_GT(s.triangle_count(), 1000u);
}

// A glTF with one 120-triangle mesh drawn 5 times by EXT_mesh_gpu_instancing.
std::string gpu_instanced_file(const std::string& dir) {
  GltfBuilder b;
  b.grid_mesh("leaves", 10, 6);
  std::vector<float> t;
  for (int i = 0; i < 5; ++i)
    t.insert(t.end(), {1.5f * float(i), 0.0f, -0.5f * float(i)});
  b.node({{"mesh", 0},
          {"extensions",
           {{"EXT_mesh_gpu_instancing",
             {{"attributes", {{"TRANSLATION", b.floats(t, "VEC3", 3)}}}}}}}});
  b.json()["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  const std::string path = dir + "/gpu.gltf";
  write_file(path, b.text());
  return path;
}

TEST(GpuInstancing, LoadsWithTheRightCountAndDrawsEveryInstance) {
  const std::string dir = temp_dir("gpu-instancing");
  const std::string path = gpu_instanced_file(dir);
  const Json j = info_json(path);
  EXPECT_EQ(j["instances"], 5);
  EXPECT_EQ(j["triangles"], 5 * 120);
  EXPECT_EQ(j["distinct_triangles"], 120);
  const RunResult r = run_sylva("buffers " + path +
                                " --buffers id --id object --format exr --cryptomatte none "
                                "--size 300x120 --elevation 0 --azimuth 0 --out-dir " +
                                dir + "/b");
  ASSERT_EQ(r.status, 0) << r.output;
  const cv::Mat ids = oiio_channels(dir + "/b/buffers.exr", "id", dir);
  std::set<int32_t> seen;
  for (auto it = ids.begin<int32_t>(); it != ids.end<int32_t>(); ++it)
    if (*it) seen.insert(*it);
  EXPECT_EQ(seen, (std::set<int32_t>{1, 2, 3, 4, 5}));  // an object id per instance
}

TEST(GpuInstancing, BadAccessorsAreOneLineErrors) {
  const std::string dir = temp_dir("gpu-instancing-bad");
  for (const auto& [name, type, per] :
       {std::tuple<const char*, const char*, size_t>{"TRANSLATION", "VEC2", 2},
        {"SCALE", "SCALAR", 1}}) {
    GltfBuilder b;
    b.grid_mesh("leaves", 10, 6);
    const std::vector<float> v(3 * per, 1.0f);
    const std::vector<float> t = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};  // 4, not 3
    Json attributes = {{name, b.floats(v, type, per)}};
    if (std::string(name) == "SCALE") attributes["TRANSLATION"] = b.floats(t, "VEC3", 3);
    b.node(
        {{"mesh", 0}, {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", attributes}}}}}});
    const std::string path = dir + "/" + name + ".gltf";
    write_file(path, b.text());
    expect_input_error("info " + path, name);
    expect_input_error("render " + path + " --size 32 -o " + dir + "/x.png", name);
  }
  EXPECT_FALSE(file_exists(dir + "/x.png"));
}

TEST(Park, TheLargestCountIsAccepted) {
  const std::string out = temp_dir("park-max") + "/max.glb";
  const RunResult r =
      run_sylva("sample park --plants " + lone_tree() + " --count 100000 --area 1000 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(info_json(out)["instances"], 100000);
}

// The camera nodes of a .glb: name -> its node's matrix.
std::map<std::string, glm::mat4> camera_nodes(const std::string& path) {
  std::map<std::string, glm::mat4> out;
  const Json gltf = glb_json(path);
  for (const Json& n : gltf["nodes"]) {
    if (!n.contains("camera")) continue;
    glm::mat4 m(1.0f);
    for (int i = 0; i < 16; ++i)
      m[i / 4][i % 4] = n["matrix"][size_t(i)].get<float>();
    out[n["name"].get<std::string>()] = m;
  }
  return out;
}

TEST(Cameras, CameraJsonIsTheFileCameraNode) {
  const std::string dir = temp_dir("cameras");
  const auto nodes = camera_nodes(park());
  ASSERT_EQ(nodes.size(), 2u);
  for (const auto& [name, world] : nodes) {
    const std::string out = dir + "/" + name;
    const std::string which = name == "plan" ? "0" : "overview";  // by index and by name
    const RunResult r = run_sylva("buffers " + park() + " --camera " + which +
                                  " --buffers depth --size 160x120 --out-dir " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    const Json cam = Json::parse(read_file(out + "/camera.json"));
    const glm::mat4 view = glm::inverse(world);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(cam["eye"][size_t(k)].get<float>(), world[3][k], 1e-4f) << name;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        EXPECT_NEAR(cam["view"][size_t(i)][size_t(j)].get<float>(), view[j][i], 1e-4f) << name;
    EXPECT_EQ(cam["orthographic"], name == "plan");
    // The file's clipping planes.
    const Json file_camera = glb_json(park())["cameras"][name == "plan" ? 0 : 1];
    const Json& planes = file_camera[name == "plan" ? "orthographic" : "perspective"];
    EXPECT_NEAR(cam["near"].get<double>(), planes["znear"].get<double>(), 1e-6);
    EXPECT_NEAR(cam["far"].get<double>(), planes["zfar"].get<double>(), 1e-4);
    const cv::Mat depth = cv::imread(out + "/depth.tiff", cv::IMREAD_UNCHANGED);
    EXPECT_GT(cv::countNonZero(depth), 500) << name;  // the park is in view
  }
}

TEST(Cameras, AMissingCameraIsAnErrorListingTheFilesCameras) {
  const std::string dir = temp_dir("cameras-bad");
  const std::string out = " --size 64 -o " + dir + "/x.png";
  const RunResult r = run_sylva("render " + park() + " --camera nope" + out);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find("--camera: no camera named 'nope'; the file's cameras: 0 'plan' "
                          "(orthographic), 1 'overview' (perspective)"),
            std::string::npos)
      << r.output;
  expect_input_error("render " + park() + " --camera 2" + out, "index 2 is out of range");
  expect_input_error("render " + lone_tree() + " --camera 0" + out, "the file has no cameras");
  EXPECT_FALSE(file_exists(dir + "/x.png"));
}

TEST(Cameras, TurntableStartsFromTheFileCamera) {
  const std::string dir = temp_dir("cameras-turntable");
  ASSERT_EQ(
      run_sylva("render " + park() + " --camera overview --size 96x64 -o " + dir + "/r.png").status,
      0);
  const RunResult t = run_sylva("turntable " + park() +
                                " --camera overview --frames 4 --size 96x64 -q -o " + dir + "/f");
  ASSERT_EQ(t.status, 0) << t.output;
  EXPECT_EQ(failing_share(dir + "/r.png", dir + "/f/frame-00000.png"), 0.0);
  EXPECT_GT(failing_share(dir + "/r.png", dir + "/f/frame-00001.png"), 0.0);
}

}  // namespace
}  // namespace sylva::test
