#include "core/scene/gltf_read.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <variant>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/scene/glb_container.h"
#include "core/scene/gltf_accessor.h"
#include "core/scene/gltf_limits.h"
#include "core/scene/gltf_nodes.h"
#include "core/scene/gltf_primitives.h"
#include "core/scene/load.h"
#include "core/scene/texture_decode.h"

namespace sylva {
namespace {

using Json = nlohmann::json;

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ')
    s.pop_back();
  return s;
}

// Keeps the encoded bytes; decoding happens later with checked buffer ranges, and only for
// the images a base colour actually uses.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

class Reader {
 public:
  Reader(const std::string& path, const tinygltf::Model& model, const Json& json)
      : m_path(path), m_model(model), m_json(json), m_accessors(model, path) {}

  Scene read() {
    read_materials();
    read_nodes();
    return std::move(m_scene);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(m_path, what); }

  void read_materials() {
    m_texture_of_image.assign(m_model.images.size(), -1);
    for (const tinygltf::Material& src : m_model.materials) {
      Material mat;
      mat.name = src.name;
      const auto& f = src.pbrMetallicRoughness.baseColorFactor;
      if (f.size() == 4)
        mat.base_color = glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
      const int tex = src.pbrMetallicRoughness.baseColorTexture.index;
      if (tex >= 0) mat.base_color_texture = texture(tex);
      if (src.pbrMetallicRoughness.baseColorTexture.texCoord != 0)
        m_scene.report.warn("texcoord", "material '" + src.name +
                                            "': base colour uses TEXCOORD_1+, read as TEXCOORD_0");
      if (src.alphaMode == "MASK")
        mat.alpha_mode = AlphaMode::Mask;
      else if (src.alphaMode == "BLEND")
        mat.alpha_mode = AlphaMode::Blend;
      else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty())
        fail("material '" + src.name + "': alphaMode '" + src.alphaMode +
             "' is not OPAQUE, MASK or BLEND");
      mat.alpha_cutoff = float(src.alphaCutoff);
      if (!(mat.alpha_cutoff >= 0.0f && mat.alpha_cutoff <= 1.0f))
        fail("material '" + src.name + "': alphaCutoff must be in [0, 1]");
      mat.double_sided = src.doubleSided;
      if (mat.alpha_mode != AlphaMode::Opaque && mat.base_color_texture >= 0 &&
          opaque(m_scene.textures[size_t(mat.base_color_texture)]))
        m_scene.report.warn(
            "opaque alpha",
            "material '" + src.name + "': alpha " + alpha_mode_name(mat.alpha_mode) +
                " but its base colour texture has no alpha (every texel opaque), so only the "
                "geometry shapes the leaves");
      m_scene.materials.push_back(mat);
    }
  }

  static bool opaque(const Texture& t) {
    for (size_t i = 3; i < t.rgba.size(); i += 4)
      if (t.rgba[i] != 255) return false;
    return true;
  }

  int texture(int tex) {
    if (size_t(tex) >= m_model.textures.size())
      fail("texture " + std::to_string(tex) + " does not exist");
    const int src = m_model.textures[size_t(tex)].source;
    if (src < 0 || size_t(src) >= m_model.images.size())
      fail("texture " + std::to_string(tex) + " has no valid image source");
    if (m_texture_of_image[size_t(src)] >= 0) return m_texture_of_image[size_t(src)];
    std::vector<std::string> decoder_warnings;
    m_scene.textures.push_back(decode(size_t(src), decoder_warnings));
    for (const std::string& w : decoder_warnings)
      m_scene.report.warn("image decoder", w);
    return m_texture_of_image[size_t(src)] = int(m_scene.textures.size() - 1);
  }

  Texture decode(size_t index, std::vector<std::string>& warnings) const {
    const tinygltf::Image& img = m_model.images[index];
    const std::string what =
        "image " + std::to_string(index) + (img.name.empty() ? "" : " '" + img.name + "'");
    const std::string name = img.name.empty() ? img.uri : img.name;
    if (img.bufferView < 0) {
      if (img.image.empty() && !img.uri.empty())
        fail("missing texture file '" + img.uri + "' (" + what + ")");
      return decode_texture(img.image.data(), img.image.size(), name, m_path, what, warnings);
    }
    if (size_t(img.bufferView) >= m_model.bufferViews.size()) fail(what + ": no such bufferView");
    const tinygltf::BufferView& view = m_model.bufferViews[size_t(img.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= m_model.buffers.size())
      fail(what + ": no such buffer");
    const std::vector<unsigned char>& buffer = m_model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
      fail(what + ": bufferView runs past the end of its buffer");
    return decode_texture(buffer.data() + view.byteOffset, view.byteLength, name, m_path, what,
                          warnings);
  }

  // Every mesh placed where the node tree puts it (gltf_nodes.h): a flat scene in world space,
  // or the plants in their own space with their instances (the meshes outside every plant
  // first, as a plant with one instance at the identity).
  void read_nodes() {
    const NodePlan plan = plan_nodes(m_path, m_model, m_json, m_accessors);
    GltfPrimitiveReader primitives(m_path, m_model, m_json, m_accessors, m_scene.materials.size(),
                                   m_scene.report);
    std::vector<int> plant_index(plan.plants.size(), -1);
    for (size_t p = 0; p < plan.plants.size(); ++p) {
      Plant plant;
      plant.name = plan.plants[p].name;
      for (const MeshPlacement& at : plan.plants[p].meshes) {
        const std::string& node_name = m_model.nodes[size_t(at.node)].name;
        for (const LocalPrimitive& lp : primitives.read(at.mesh, node_name)) {
          plant.meshes.push_back(uint32_t(m_scene.meshes.size()));
          m_scene.meshes.push_back(
              place_primitive(lp, at.transform, primitives.name(at.mesh, node_name, lp)));
        }
      }
      if (!plan.instanced() || plant.meshes.empty()) continue;
      const int root = plan.plants[p].root_node;
      plant.hierarchy =
          root >= 0 ? read_hierarchy(json_at({"nodes", size_t(root), "extras", "sylva_hierarchy"}))
                    : scene_hierarchy();
      plant_index[p] = int(m_scene.plants.size());
      m_scene.plants.push_back(std::move(plant));
    }
    read_cameras(plan);
    if (!plan.instanced()) {
      m_scene.hierarchy = scene_hierarchy();
      return;
    }
    if (plant_index[0] >= 0)
      m_scene.instances.push_back({uint32_t(plant_index[0]), glm::mat4(1.0f), ""});
    for (const InstancePlan& inst : plan.instances)
      add_instance(inst, plant_index[inst.plant]);
  }

  // The placed cameras; one with impossible parameters (a zero field of view, far before near,
  // a scale of zero) is left out with a warning.
  void read_cameras(const NodePlan& plan) {
    for (const CameraPlacement& at : plan.cameras) {
      const tinygltf::Camera& src = m_model.cameras[size_t(at.camera)];
      SceneCamera c;
      c.name = m_model.nodes[size_t(at.node)].name;
      if (c.name.empty()) c.name = src.name;
      if (c.name.empty()) c.name = "camera " + std::to_string(m_scene.cameras.size());
      std::string bad;
      c.orthographic = src.type == "orthographic";
      if (c.orthographic) {
        c.xmag = float(std::abs(src.orthographic.xmag));
        c.ymag = float(std::abs(src.orthographic.ymag));
        c.znear = float(src.orthographic.znear);
        c.zfar = float(src.orthographic.zfar);
        if (!(c.xmag > 0.0f && c.ymag > 0.0f && std::isfinite(c.xmag) && std::isfinite(c.ymag)))
          bad = "xmag and ymag must be non-zero";
        else if (!(c.znear >= 0.0f && c.zfar > c.znear && std::isfinite(c.zfar)))
          bad = "needs 0 <= znear < zfar";
      } else if (src.type == "perspective") {
        c.yfov = float(src.perspective.yfov);
        c.aspect = float(src.perspective.aspectRatio);
        c.znear = float(src.perspective.znear);
        c.zfar = float(src.perspective.zfar);
        if (!(c.yfov > 0.0f && c.yfov < 3.14159f))
          bad = "yfov must be in (0, pi)";
        else if (!(c.znear > 0.0f && std::isfinite(c.znear)))
          bad = "znear must be > 0";
        else if (!(c.zfar == 0.0f || (c.zfar > c.znear && std::isfinite(c.zfar))))
          bad = "zfar must be above znear";
        if (!(c.aspect >= 0.0f && std::isfinite(c.aspect))) c.aspect = 0.0f;
      } else {
        bad = "type '" + src.type + "' is not perspective or orthographic";
      }
      if (bad.empty() && !rigid(at.world, c.to_world)) bad = "its node's transform is singular";
      if (!bad.empty()) {
        m_scene.report.warn("camera", "camera '" + c.name + "': " + bad + "; left out");
        continue;
      }
      m_scene.cameras.push_back(c);
    }
  }

  // `world` without its scale (glTF cameras ignore it); false when an axis vanishes.
  static bool rigid(const glm::dmat4& world, glm::mat4& out) {
    glm::dmat4 m = world;
    for (int c = 0; c < 3; ++c) {
      const double len = glm::length(glm::dvec3(m[c]));
      if (!(len > 1e-12) || !std::isfinite(len)) return false;
      m[c] /= len;
    }
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        if (!std::isfinite(m[c][r])) return false;
    out = glm::mat4(m);
    return true;
  }

  // A zero scale hides an instance (some exporters do that): left out, with a warning.
  void add_instance(const InstancePlan& inst, int plant) {
    if (plant < 0) return;  // its primitives were all points, lines or empty
    const glm::mat4 t(inst.world);
    const double det = glm::determinant(glm::dmat3(glm::dmat4(t)));
    double scale = 0.0;
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        scale = std::max(scale, std::abs(double(t[c][r])));
    if (std::isfinite(det) && std::abs(det) <= 1e-12 * scale * scale * scale) {
      m_scene.report.warn("zero scale", "instance '" + inst.name + "' of plant '" +
                                            m_scene.plants[size_t(plant)].name +
                                            "' has a zero scale: not drawn");
      return;
    }
    m_scene.instances.push_back({uint32_t(plant), t, inst.name});
  }

  const Json* json_at(std::initializer_list<std::variant<const char*, size_t>> keys) const {
    return sylva::json_at(m_json, keys);
  }

  Hierarchy scene_hierarchy() const {
    const int s = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
    const Json* h = json_at({"scenes", size_t(s), "extras", "sylva_hierarchy"});
    if (!h) h = json_at({"asset", "extras", "sylva_hierarchy"});
    return read_hierarchy(h);
  }

  Hierarchy read_hierarchy(const Json* h) const {
    Hierarchy out;
    if (!h) return out;
    if (!h->is_object()) fail("sylva_hierarchy must be an object");
    auto array = [&](const char* key, auto& values) {
      if (!h->contains(key) || !(*h)[key].is_array())
        fail(std::string("sylva_hierarchy.") + key + " must be an array");
      for (const Json& v : (*h)[key]) {
        if (!v.is_number()) fail(std::string("sylva_hierarchy.") + key + " must hold numbers");
        const double d = v.get<double>();
        using T = typename std::decay_t<decltype(values)>::value_type;
        if (std::is_integral_v<T> && (d != std::floor(d) || std::abs(d) > 2e9))
          fail(std::string("sylva_hierarchy.") + key + " must hold integers");
        values.push_back(T(d));
      }
    };
    array("branch_parent", out.branch_parent);
    array("branch_diameter", out.branch_diameter);
    array("leaf_branch", out.leaf_branch);
    validate_hierarchy(out, m_path);
    return out;
  }

  const std::string& m_path;
  const tinygltf::Model& m_model;
  const Json& m_json;
  GltfAccessorReader m_accessors;
  Scene m_scene;
  std::vector<int> m_texture_of_image;
};

// Extensions a file may require that this reader honours (quantized attributes are read as
// normalized integers; unlit needs nothing; instancing: gltf_nodes.h).
bool supported_extension(const std::string& e) {
  return e == "KHR_materials_unlit" || e == "KHR_mesh_quantization" ||
         e == "EXT_mesh_gpu_instancing";
}

}  // namespace

Scene read_gltf(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  if (bytes.empty()) throw InputError(path, "empty file");
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = ext == ".glb";
  size_t length = 0;
  const std::string json_text = binary ? glb_json_chunk(path, bytes, length) : bytes;
  // Depth and counts first, in one pass that builds nothing (core/scene/gltf_limits.h): before
  // the JSON tree, and tinygltf's model, are allocated in proportion to them.
  try {
    check_gltf_json(path, json_text);
  } catch (const InputError& e) {
    throw InputError(path, one_line(e.reason()));
  }
  Json json;
  try {
    json = Json::parse(json_text);
  } catch (const Json::exception& e) {
    throw InputError(path, "invalid JSON: " + one_line(e.what()));
  }
  if (!json.is_object()) throw InputError(path, "invalid glTF: the JSON is not an object");
  check_gltf_limits(path, json);
  if (json.contains("extensionsRequired") && json["extensionsRequired"].is_array()) {
    std::string missing;
    for (const Json& e : json["extensionsRequired"])
      if (!e.is_string() || !supported_extension(e.get<std::string>()))
        missing +=
            (missing.empty() ? "" : ", ") + (e.is_string() ? e.get<std::string>() : e.dump());
    if (!missing.empty())
      throw InputError(path, "requires unsupported glTF extension(s) " + missing +
                                 "; supported: KHR_materials_unlit, KHR_mesh_quantization, "
                                 "EXT_mesh_gpu_instancing");
  }

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                              reinterpret_cast<const unsigned char*>(bytes.data()),
                                              unsigned(length), base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                             unsigned(bytes.size()), base_dir);
  } catch (const std::exception& e) {
    throw InputError(path, "invalid glTF: " + one_line(e.what()));
  }
  if (!ok)
    throw InputError(path, "invalid glTF: " + one_line(err.empty() ? "tinygltf failed" : err));
  Scene scene = Reader(path, model, json).read();
  if (!warn.empty()) scene.report.warnings.push_back("tinygltf: " + one_line(warn));
  return scene;
}

}  // namespace sylva
