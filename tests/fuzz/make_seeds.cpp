// Writes the seed corpora of the fuzz harnesses (tests/fuzz/README.md) into OUT/<harness>/:
// small slices of the shared trees (the first triangles of their first meshes, textures cut
// to 16 px) and of the sample plants as .glb, .gltf (buffers as data: URIs), .obj, .ply
// (ASCII and binary), .off and .stl (ASCII and binary); each shared tree's own JSON chunk
// with the start of its binary chunk; hand-written OBJ variants; small PNG and JPEG textures cut
// from the trees' textures; the built-in presets; `--set` lines of every parameter's default;
// option strings; a blob keyframe; a foliage cache file of the cache harness's scene.
//
//   make_seeds OUT SHARED_ASSETS_DIR
#if defined(__GNUC__) && !defined(__clang__)  // GCC only; clang has no such warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/codecs.h"
#include "core/scene/glb_container.h"
#include "core/scene/gltf_write.h"
#include "npr/blob_keyframes.h"
#include "samples/park.h"
#include "styles/presets.h"
#include "styles/style_params.h"
#include "tests/fuzz/fuzz_scenes.h"
#include "tests/openmesh_copy.h"

namespace fs = std::filesystem;
using namespace sylva;

namespace {

void put(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The first `triangles` triangles of each of the first `meshes` meshes, vertices compacted,
// textures cut down to at most 16 px; no hierarchy (it would not fit the slice).
Scene slice(const Scene& full, size_t meshes, size_t triangles) {
  Scene s;
  s.materials = full.materials;
  for (const Texture& t : full.textures) {
    cv::Mat m(t.height, t.width, CV_8UC4, const_cast<uint8_t*>(t.rgba.data())), small;
    cv::resize(m, small, cv::Size(std::min(t.width, 16), std::min(t.height, 16)), 0, 0,
               cv::INTER_AREA);
    Texture c = t;
    c.width = small.cols, c.height = small.rows;
    c.rgba.assign(small.data, small.data + small.total() * 4);
    s.textures.push_back(c);
  }
  for (size_t i = 0; i < std::min(meshes, full.meshes.size()); ++i) {
    const Mesh& m = full.meshes[i];
    Mesh c;
    c.name = m.name, c.material = m.material;
    std::vector<int> remap(m.positions.size(), -1);
    for (size_t k = 0; k < std::min(m.indices.size(), triangles * 3); ++k) {
      const uint32_t v = m.indices[k];
      if (remap[v] < 0) {
        remap[v] = int(c.positions.size());
        c.positions.push_back(m.positions[v]);
        c.normals.push_back(m.normals[v]);
        if (!m.uvs.empty()) c.uvs.push_back(m.uvs[v]);
        if (!m.colors.empty()) c.colors.push_back(m.colors[v]);
      }
      c.indices.push_back(uint32_t(remap[v]));
    }
    if (!m.roles.empty()) c.roles.assign(m.roles.begin(), m.roles.begin() + c.indices.size() / 3);
    s.meshes.push_back(std::move(c));
  }
  return s;
}

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t v = uint8_t(in[i]) << 16;
    if (i + 1 < in.size()) v |= uint8_t(in[i + 1]) << 8;
    if (i + 2 < in.size()) v |= uint8_t(in[i + 2]);
    for (size_t k = 0; k < 4; ++k)
      out += k <= (in.size() - i) ? t[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// The .glb as a .gltf whose buffer is a base64 data: URI.
std::string as_gltf(const std::string& glb) {
  size_t length = 0;
  nlohmann::json j = nlohmann::json::parse(glb_json_chunk("seed", glb, length));
  const size_t bin_at = 20 + glb_le32(glb, 12);
  if (bin_at + 8 <= length && j.contains("buffers")) {
    const std::string bin = glb.substr(bin_at + 8, glb_le32(glb, bin_at));
    j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(bin);
  }
  return j.dump();
}

// The slice's first mesh through OpenMesh's writers: .obj, .off, .ply and .stl, binary too.
void write_meshes(const Scene& s, const fs::path& out, const std::string& stem) {
  if (s.meshes.empty()) return;
  const test::TriMesh tm = test::openmesh_copy(s.meshes[0]);
  using O = OpenMesh::IO::Options;
  const struct {
    const char* dir;
    const char* suffix;
    O::Flag flags;
  } kinds[] = {{"obj", ".obj", O::Flag(O::VertexNormal | O::VertexTexCoord)},
               {"off", ".off", O::Flag(O::VertexColor)},
               {"ply", ".ply", O::Flag(O::VertexNormal | O::VertexColor)},
               {"ply", "_bin.ply", O::Flag(O::Binary | O::VertexNormal | O::VertexColor)},
               {"stl", ".stl", O::Flag(O::Default)},
               {"stl", "_bin.stl", O::Flag(O::Binary)}};
  for (const auto& k : kinds) {
    const fs::path dir = out / k.dir;
    fs::create_directories(dir);
    std::string name = stem + k.suffix;
    // OpenMesh chooses the writer by extension, so a binary file is written as X.ply first.
    const std::string suffix = k.suffix;
    const fs::path tmp = dir / ("tmp" + suffix.substr(suffix.rfind('.')));
    if (!OpenMesh::IO::write_mesh(tm, tmp.string(), O(k.flags)))
      throw std::runtime_error("cannot write " + tmp.string());
    fs::rename(tmp, dir / name);
  }
}

// Small PNGs (RGBA, RGB, grey, 16-bit) and a JPEG cut from a scene's first texture.
void write_textures(const Scene& s, const fs::path& dir, const std::string& stem) {
  if (s.textures.empty()) return;
  const Texture& t = s.textures[0];
  cv::Mat rgba(t.height, t.width, CV_8UC4, const_cast<uint8_t*>(t.rgba.data())), bgr, grey, deep;
  cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  bgr.convertTo(deep, CV_16U, 257.0);
  cv::Mat bgra;
  cv::cvtColor(rgba, bgra, cv::COLOR_RGBA2BGRA);
  const std::pair<std::string, cv::Mat> images[] = {{"_rgba.png", bgra},
                                                    {"_rgb.png", bgr},
                                                    {"_grey.png", grey},
                                                    {"_16.png", deep},
                                                    {".jpg", bgr}};
  for (const auto& [suffix, image] : images) {
    std::vector<uchar> bytes;
    if (!codecs().encode(suffix.substr(suffix.rfind('.')), image, bytes, {}))
      throw std::runtime_error("cannot encode " + suffix);
    put(dir, stem + suffix, std::string(bytes.begin(), bytes.end()));
  }
}

// One scene's seeds: .glb and .gltf, the meshes, the textures.
void write_scene_seeds(const Scene& s, const fs::path& out, const std::string& stem) {
  const fs::path glb = out / "glb" / (stem + ".glb");
  fs::create_directories(glb.parent_path());
  write_glb(s, glb.string());
  put(out / "gltf", stem + ".gltf", as_gltf(file_bytes(glb)));
  write_meshes(s, out, stem);
  write_textures(s, out / "texture", stem);
}

// The asset's own JSON chunk (its real structure: samplers, extensions, node tree) with the
// first 2 KB of its binary chunk.
void write_asset_json_seed(const fs::path& asset, const fs::path& out) {
  const std::string bytes = file_bytes(asset);
  size_t length = 0;
  const std::string json = glb_json_chunk(asset.string(), bytes, length);
  const size_t bin_at = 20 + glb_le32(bytes, 12);
  const std::string bin =
      bin_at + 8 <= length
          ? bytes.substr(bin_at + 8, std::min<size_t>(2048, glb_le32(bytes, bin_at)))
          : std::string();
  put(out / "glb", asset.stem().string() + "_json.glb", glb_assemble(json, bin));
  put(out / "gltf", asset.stem().string() + "_json.gltf", json);
}

void write_parameter_seeds(const fs::path& out) {
  for (const PresetFile& p : builtin_preset_files())
    put(out / "preset", p.name + ".toml", p.text);
  put(out / "preset", "user.toml",
      "description = \"a user's preset\"\ninherits = [\"ink\", \"toon\"]\n[edges]\nwidth = 2.5\n"
      "[toon]\nbands = 4\n");
  StyleParams params;
  ParamSet set;
  bind_style_params(set, params);
  std::map<std::string, std::string> sections;
  for (const ParamSpec& spec : set.specs())
    sections[spec.key.substr(0, spec.key.find('.'))] += spec.key + "=" + spec.default_text + "\n";
  for (const auto& [section, lines] : sections)
    put(out / "set", section + ".txt", lines);
  const char* options[] = {
      "\0"
      "512x256",
      "\0"
      "1024",
      "\1"
      "dir:-1,2,3",
      "\1"
      "point:0,5,2:0.5:scene",
      "\2"
      "white",
      "\2"
      "#a0b0c0",
      "\3"
      "#102030"};
  for (size_t i = 0; i < std::size(options); ++i)
    put(out / "options", "option" + std::to_string(i) + ".txt",
        std::string(options[i], 1 + std::strlen(options[i] + 1)));
}

void write_cache_seeds(const fs::path& out) {
  std::vector<BlobOutline> blobs(3);
  for (size_t i = 0; i < blobs.size(); ++i) {
    blobs[i].cluster = uint32_t(i + 2), blobs[i].pixels = int(40 * i + 7);
    blobs[i].min_depth = 2.5f + float(i), blobs[i].opacity = i == 1 ? 0.5f : 1.0f;
    blobs[i].wrap.center = {30.0f + 10 * i, 40.0f}, blobs[i].wrap.radius = 12.5f;
    for (int k = 0; k < 6; ++k)
      blobs[i].wrap.points.push_back({30.0f + 12 * std::cos(k), 40.0f + 12 * std::sin(k)});
  }
  put(out / "keyframes", "key.txt", format_blob_outlines(blobs));
  const fuzz::CacheScene& c = fuzz::cache_scene();
  const ResultCache cache((out / "cache").string());
  FoliageIllumination f = compute_foliage_illumination(c.scene, c.params);
  // The stage timings are measured, so they differ from run to run; the seed must not.
  f.stats.seconds_field = f.stats.seconds_surface = f.stats.seconds_shading = 0;
  if (!cache.store(c.kind, c.key, serialize_foliage(f)))
    throw std::runtime_error("cannot write the cache seed");
}

}  // namespace

// Hand-written OBJ text with what OpenMesh's writer never writes: `v x y z w`, vertex colours,
// one- and three-number `vt`, relative indices, polygons, ignored statements, comments, CRLF.
void write_obj_seeds(const fs::path& out) {
  put(out / "obj", "variants.obj",
      "# variants\nmtllib a.mtl\no plant\ng leaf\ns 1\nusemtl green\nv 0 0 0 1\nv 1 0 0 1\n"
      "v 1 1 0 0.5\nv 0 1 0 1\nv .5 1.5 -0.25e-1 1\nvt 0\nvt 1 0 0\nvt 1 1\nvn 0 0 1\n"
      "vn 0 0 -1\nf 1/1/1 2/2/1 3/3/1 4/1/1 5/2/1\nf -1//-2 -3//-2 -4//-2\nl 1 2\np 3\n");
  put(out / "obj", "colours.obj",
      "v 0 0 0 1 0 0\r\nv 1 0 0 0 1 0\r\nv 0 1 0 0 0 1\r\nv 1 1 0 0.5 0.5 0.5\r\n"
      "f 1 2 3\r\nf 2 4 3 # a quad's second half\r\n");
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_seeds OUT SHARED_ASSETS_DIR\n";
    return 2;
  }
  const fs::path out = argv[1];
  omlog().disable();  // the writers' "[OBJWriter] : write file" lines
  try {
    for (PlantKind kind : {PlantKind::Tree, PlantKind::Bush, PlantKind::Conifer}) {
      PlantOptions o;
      o.kind = kind, o.leaves = 100;
      write_scene_seeds(slice(make_plant(o), 2, 60), out,
                        std::string("sample_") + plant_kind_name(kind));
    }
    {
      // A scene of many plants: shared meshes, instance nodes marked sylva_plant, cameras.
      PlantOptions o;
      o.leaves = 100;
      ParkOptions po;
      po.count = 3;
      po.width = po.depth = 10.0f;
      write_scene_seeds(make_park({slice(make_plant(o), 2, 60)}, {"tree"}, po), out, "park");
    }
    std::vector<fs::path> assets;
    for (const auto& e : fs::directory_iterator(argv[2]))
      if (e.path().extension() == ".glb") assets.push_back(e.path());
    std::sort(assets.begin(), assets.end());
    for (const fs::path& a : assets) {
      write_scene_seeds(slice(load_scene(a.string()), 4, 12), out, a.stem().string());
      write_asset_json_seed(a, out);
    }
    write_parameter_seeds(out);
    write_cache_seeds(out);
    write_obj_seeds(out);
  } catch (const std::exception& e) {
    std::cerr << "make_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
