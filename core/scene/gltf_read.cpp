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

Role parse_role(const Json& extras, bool& found) {
  found = false;
  if (!extras.is_object() || !extras.contains("sylva_role") || !extras["sylva_role"].is_string())
    return Role::Other;
  const std::string r = extras["sylva_role"].get<std::string>();
  found = true;
  if (r == "foliage") return Role::Foliage;
  if (r == "wood") return Role::Wood;
  if (r == "ground") return Role::Ground;
  if (r == "grass") return Role::Grass;
  if (r != "other") found = false;
  return Role::Other;
}

class Reader {
 public:
  Reader(const std::string& path, const tinygltf::Model& model, const Json& json)
      : m_path(path), m_model(model), m_json(json), m_accessors(model, path) {}

  Scene read() {
    read_materials();
    read_nodes();
    read_hierarchy();
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

  static glm::dmat4 local_matrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
      glm::dmat4 m;
      for (int i = 0; i < 16; ++i)
        m[i / 4][i % 4] = node.matrix[size_t(i)];
      return m;
    }
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3)
      m = glm::translate(m,
                         glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
      m *= glm::mat4_cast(glm::normalize(
          glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])));
    if (node.scale.size() == 3)
      m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
  }

  void read_nodes() {
    const size_t n = m_model.nodes.size();
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i) {
      for (int c : m_model.nodes[i].children) {
        if (c < 0 || size_t(c) >= n)
          fail("node " + std::to_string(i) + " has a missing child " + std::to_string(c));
        if (parent[size_t(c)] != -1 || size_t(c) == i)
          fail("node " + std::to_string(c) + " has more than one parent (glTF needs a tree)");
        parent[size_t(c)] = int(i);
      }
    }
    std::vector<int> roots;
    const int s =
        m_model.defaultScene >= 0 ? m_model.defaultScene : (m_model.scenes.empty() ? -1 : 0);
    if (s >= int(m_model.scenes.size()))
      fail("the default scene " + std::to_string(s) + " does not exist");
    if (s >= 0) {
      roots = m_model.scenes[size_t(s)].nodes;
      for (int r : roots) {
        if (r < 0 || size_t(r) >= n)
          fail("scene " + std::to_string(s) + " refers to a missing node");
        if (parent[size_t(r)] != -1) fail("scene root node " + std::to_string(r) + " has a parent");
      }
    } else {
      for (size_t i = 0; i < n; ++i)
        if (parent[i] == -1) roots.push_back(int(i));
    }
    // With one parent per node and parentless roots there is no cycle; walk iteratively so
    // deep chains cannot overflow the stack.
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.emplace_back(*it, glm::dmat4(1.0));
    std::vector<char> seen(n, 0);
    while (!stack.empty()) {
      auto [i, parent_world] = stack.back();
      stack.pop_back();
      if (seen[size_t(i)]) fail("node " + std::to_string(i) + " appears twice in the scene");
      seen[size_t(i)] = 1;
      const tinygltf::Node& node = m_model.nodes[size_t(i)];
      const glm::dmat4 world = parent_world * local_matrix(node);
      if (node.mesh >= 0) add_mesh(node, world);
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
        stack.emplace_back(*c, world);
    }
  }

  void add_mesh(const tinygltf::Node& node, const glm::dmat4& world) {
    if (size_t(node.mesh) >= m_model.meshes.size())
      fail("node '" + node.name + "' refers to a missing mesh");
    const tinygltf::Mesh& src = m_model.meshes[size_t(node.mesh)];
    const Json* jmesh = json_at({"meshes", size_t(node.mesh)});
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool flip = glm::determinant(glm::dmat3(world)) < 0.0;
    for (size_t k = 0; k < src.primitives.size(); ++k) {
      const tinygltf::Primitive& prim = src.primitives[k];
      std::string name = !src.name.empty()    ? src.name
                         : !node.name.empty() ? node.name
                                              : "mesh" + std::to_string(node.mesh);
      // Appended piecewise: "[" + std::string&& trips a GCC 12 -Wrestrict false positive.
      if (src.primitives.size() > 1) name.append("[").append(std::to_string(k)).append("]");
      if (prim.mode >= 0 && prim.mode <= 3) {
        m_scene.report.warn("points/lines", "mesh '" + name + "': points/lines primitive skipped");
        continue;
      }
      if (prim.mode < 0 || prim.mode > 6)
        fail("mesh '" + name + "': unknown primitive mode " + std::to_string(prim.mode));
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end()) {
        m_scene.report.warn("no POSITION",
                            "mesh '" + name + "': primitive without POSITION skipped");
        continue;
      }
      Mesh mesh;
      mesh.name = name;
      mesh.material = prim.material;
      if (prim.material >= int(m_scene.materials.size()) || prim.material < -1)
        fail("mesh '" + name + "': material does not exist");
      int comps = 0;
      const std::string where = "mesh '" + name + "'";
      std::vector<float> p = m_accessors.floats(pos->second, comps, "POSITION");
      if (comps != 3) fail(where + ": POSITION must be VEC3");
      const size_t nv = p.size() / 3;
      mesh.positions.resize(nv);
      for (size_t v = 0; v < nv; ++v)
        mesh.positions[v] =
            glm::vec3(world * glm::dvec4(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0));
      if (auto a = prim.attributes.find("NORMAL"); a != prim.attributes.end()) {
        std::vector<float> nrm = m_accessors.floats(a->second, comps, "NORMAL");
        if (comps != 3 || nrm.size() != p.size())
          fail(where + ": NORMAL must be VEC3 with one per vertex");
        mesh.normals.resize(nv);
        for (size_t v = 0; v < nv; ++v) {
          const glm::dvec3 wn =
              normal_matrix * glm::dvec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
          const double len = glm::length(wn);
          mesh.normals[v] = len > 0.0 && std::isfinite(len) ? glm::vec3(wn / len) : glm::vec3(0.0f);
        }
      }
      if (auto a = prim.attributes.find("TEXCOORD_0"); a != prim.attributes.end()) {
        std::vector<float> uv = m_accessors.floats(a->second, comps, "TEXCOORD_0");
        if (comps != 2 || uv.size() != nv * 2)
          fail(where + ": TEXCOORD_0 must be VEC2 with one per vertex");
        mesh.uvs.resize(nv);
        for (size_t v = 0; v < nv; ++v)
          mesh.uvs[v] = glm::vec2(uv[2 * v], uv[2 * v + 1]);
      }
      // A baked file's COLOR_0 is the ka preview for other engines (gltf_write.h); its real
      // vertex colours, if any, are in COLOR_1.
      const Json* marker = json_at({"meshes", size_t(node.mesh), "extras", "sylva_color_0"});
      const bool baked_colors = marker && marker->is_string() && *marker == "ambient";
      const Json* outward = json_at({"meshes", size_t(node.mesh), "extras", "sylva_normals"});
      mesh.outward_normals = outward && outward->is_string() && *outward == "outward";
      const char* color_name = baked_colors ? "COLOR_1" : "COLOR_0";
      if (auto a = prim.attributes.find(color_name); a != prim.attributes.end()) {
        std::vector<float> c = m_accessors.floats(a->second, comps, color_name);
        if ((comps != 3 && comps != 4) || c.size() != nv * size_t(comps))
          fail(where + ": " + color_name + " must be VEC3 or VEC4 with one per vertex");
        mesh.colors.resize(nv);
        for (size_t v = 0; v < nv; ++v)
          mesh.colors[v] = glm::vec4(c[comps * v], c[comps * v + 1], c[comps * v + 2],
                                     comps == 4 ? c[comps * v + 3] : 1.0f);
      }
      if (auto a = prim.attributes.find("_AMBIENT"); a != prim.attributes.end()) {
        mesh.ka = m_accessors.floats(a->second, comps, "_AMBIENT");
        if (comps != 1 || mesh.ka.size() != nv)
          fail(where + ": _AMBIENT must be SCALAR with one per vertex");
        for (size_t v = 0; v < nv; ++v)
          if (!(mesh.ka[v] >= 0.0f && mesh.ka[v] <= 1.0f))
            fail(where + ": _AMBIENT (ambient coefficient) " + std::to_string(mesh.ka[v]) +
                 " at vertex " + std::to_string(v) + " is outside [0, 1]");
      }
      std::vector<uint32_t> idx;
      if (prim.indices >= 0)
        idx = m_accessors.indices(prim.indices);
      else {
        idx.resize(nv);
        for (size_t v = 0; v < nv; ++v)
          idx[v] = uint32_t(v);
      }
      for (uint32_t i : idx)
        if (i >= nv)
          fail(where + ": vertex index " + std::to_string(i) + " out of range (" +
               std::to_string(nv) + " vertices)");
      mesh.indices = triangulate(idx, prim.mode, where);
      if (flip)
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
          std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
      if (mesh.normals.empty()) compute_vertex_normals(mesh);
      bool found = false;
      Role role = Role::Other;
      if (const Json* jp = json_at({"meshes", size_t(node.mesh), "primitives", k, "extras"}))
        role = parse_role(*jp, found);
      if (!found && jmesh && jmesh->contains("extras"))
        role = parse_role((*jmesh)["extras"], found);
      if (found) mesh.roles.assign(mesh.triangle_count(), role);
      if (!mesh.indices.empty()) m_scene.meshes.push_back(std::move(mesh));
    }
  }

  std::vector<uint32_t> triangulate(const std::vector<uint32_t>& idx, int mode,
                                    const std::string& where) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (idx.size() % 3 != 0)
        m_scene.report.warn("index count",
                            where + ": index count not a multiple of 3, extra indices ignored");
      return std::vector<uint32_t>(idx.begin(), idx.begin() + long(idx.size() / 3 * 3));
    }
    std::vector<uint32_t> out;
    for (size_t i = 0; i + 2 < idx.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)  // glTF 2.0 §3.7.2.1: odd triangles swap
        out.insert(out.end(), {idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]});
      else
        out.insert(out.end(), {idx[i + 1], idx[i + 2], idx[0]});
    }
    return out;
  }

  // The raw JSON at a path of keys and array indices, or null.
  const Json* json_at(std::initializer_list<std::variant<const char*, size_t>> keys) const {
    const Json* j = &m_json;
    for (const auto& k : keys) {
      if (std::holds_alternative<const char*>(k)) {
        if (!j->is_object() || !j->contains(std::get<const char*>(k))) return nullptr;
        j = &(*j)[std::get<const char*>(k)];
      } else {
        if (!j->is_array() || std::get<size_t>(k) >= j->size()) return nullptr;
        j = &(*j)[std::get<size_t>(k)];
      }
    }
    return j;
  }

  void read_hierarchy() {
    const int s = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
    const Json* h = json_at({"scenes", size_t(s), "extras", "sylva_hierarchy"});
    if (!h) h = json_at({"asset", "extras", "sylva_hierarchy"});
    if (!h) return;
    if (!h->is_object()) fail("sylva_hierarchy must be an object");
    auto array = [&](const char* key, auto& out) {
      if (!h->contains(key) || !(*h)[key].is_array())
        fail(std::string("sylva_hierarchy.") + key + " must be an array");
      for (const Json& v : (*h)[key]) {
        if (!v.is_number()) fail(std::string("sylva_hierarchy.") + key + " must hold numbers");
        const double d = v.get<double>();
        using T = typename std::decay_t<decltype(out)>::value_type;
        if (std::is_integral_v<T> && (d != std::floor(d) || std::abs(d) > 2e9))
          fail(std::string("sylva_hierarchy.") + key + " must hold integers");
        out.push_back(T(d));
      }
    };
    array("branch_parent", m_scene.hierarchy.branch_parent);
    array("branch_diameter", m_scene.hierarchy.branch_diameter);
    array("leaf_branch", m_scene.hierarchy.leaf_branch);
    validate_hierarchy(m_scene.hierarchy, m_path);
  }

  const std::string& m_path;
  const tinygltf::Model& m_model;
  const Json& m_json;
  GltfAccessorReader m_accessors;
  Scene m_scene;
  std::vector<int> m_texture_of_image;
};

// Extensions a file may require that this reader honours (quantized attributes are read as
// normalized integers; unlit needs nothing).
bool supported_extension(const std::string& e) {
  return e == "KHR_materials_unlit" || e == "KHR_mesh_quantization";
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
                                 "; supported: KHR_materials_unlit, KHR_mesh_quantization");
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
