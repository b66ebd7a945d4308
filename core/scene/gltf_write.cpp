#include "core/scene/gltf_write.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <type_traits>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/codecs_png.h"
#include "core/scene/glb_container.h"

namespace sylva {
namespace {

using Json = nlohmann::json;

constexpr int kFloat = 5126, kUShort = 5123, kUInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The BIN chunk and the bufferViews/accessors that point into it.
class BinBuilder {
 public:
  int view(const void* data, size_t bytes, int target) {
    while (m_bin.size() % 4)
      m_bin.push_back('\0');  // glTF: views start 4-byte aligned
    Json v = {{"buffer", 0}, {"byteOffset", m_bin.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    m_bin.append(static_cast<const char*>(data), bytes);
    m_views.push_back(v);
    return int(m_views.size() - 1);
  }

  int accessor(int view, int component_type, size_t count, const char* type) {
    m_accessors.push_back({{"bufferView", view},
                           {"componentType", component_type},
                           {"count", count},
                           {"type", type}});
    return int(m_accessors.size() - 1);
  }

  template <typename T>
  int attribute(const std::vector<T>& values, const char* type, bool with_bounds = false) {
    const int a = accessor(view(values.data(), values.size() * sizeof(T), kArrayBuffer), kFloat,
                           values.size(), type);
    if (!with_bounds) return a;  // bounds are required for POSITION only
    if constexpr (!std::is_arithmetic_v<T>) {
      T lo = values[0], hi = values[0];
      for (const T& v : values) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
      }
      Json jmin = Json::array(), jmax = Json::array();
      for (int c = 0; c < T::length(); ++c) {
        jmin.push_back(lo[c]);
        jmax.push_back(hi[c]);
      }
      m_accessors[size_t(a)]["min"] = jmin;
      m_accessors[size_t(a)]["max"] = jmax;
    }
    return a;
  }

  int indices(const std::vector<uint32_t>& idx, uint32_t max_index) {
    // 65535 is the primitive-restart value, so 16-bit indices stop one short of it.
    if (max_index < 65535) {
      std::vector<uint16_t> small(idx.begin(), idx.end());
      return accessor(view(small.data(), small.size() * 2, kElementArrayBuffer), kUShort,
                      small.size(), "SCALAR");
    }
    return accessor(view(idx.data(), idx.size() * 4, kElementArrayBuffer), kUInt, idx.size(),
                    "SCALAR");
  }

  std::string& bin() { return m_bin; }
  Json& views() { return m_views; }
  Json& accessors() { return m_accessors; }

 private:
  std::string m_bin;
  Json m_views = Json::array();
  Json m_accessors = Json::array();
};

std::string encode_png(const Texture& tex, const std::string& path) {
  cv::Mat rgba;
  if (tex.width > 0 && tex.height > 0 && tex.rgba.size() == size_t(tex.width) * tex.height * 4)
    rgba = cv::Mat(tex.height, tex.width, CV_8UC4, const_cast<uint8_t*>(tex.rgba.data()));
  else
    rgba = cv::Mat(1, 1, CV_8UC4, cv::Scalar(255, 255, 255, 255));  // keeps indices valid
  cv::Mat bgra;
  cv::cvtColor(rgba, bgra, cv::COLOR_RGBA2BGRA);
  std::string png;  // libpng with cv::imencode's settings: the same bytes, no codecs plugin
  if (!sylva::encode_png(bgra, kOpenCvPng, png))
    throw InputError(path, "cannot write: PNG encoding of texture '" + tex.name + "' failed");
  return png;
}

Json material_json(const Material& m) {
  const glm::vec4 c = glm::clamp(m.base_color, 0.0f, 1.0f);
  Json pbr = {
      {"baseColorFactor", {c.r, c.g, c.b, c.a}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}};
  if (m.base_color_texture >= 0) pbr["baseColorTexture"] = {{"index", m.base_color_texture}};
  Json j = {{"name", m.name},
            {"pbrMetallicRoughness", pbr},
            {"alphaMode", alpha_mode_name(m.alpha_mode)}};
  if (m.alpha_mode == AlphaMode::Mask) j["alphaCutoff"] = std::clamp(m.alpha_cutoff, 0.0f, 1.0f);
  if (m.double_sided) j["doubleSided"] = true;
  return j;
}

// Unit length; a zero or non-finite vector falls back to `fallback`, then to +Z.
glm::vec3 unit_normal(const glm::vec3& n, const glm::vec3* fallback) {
  const float len = glm::length(n);
  if (len > 0.0f && std::isfinite(len)) return n / len;
  if (fallback) return unit_normal(*fallback, nullptr);
  return glm::vec3(0, 0, 1);
}

// One glTF mesh; one primitive per role (in order of first appearance) so roles survive. The
// primitives share the vertex accessors, so per-vertex data stays indexed by mesh vertex.
// `normals` / `ka` replace the mesh's own when not null.
Json mesh_json(const Mesh& mesh, BinBuilder& bin, const std::vector<glm::vec3>* normals,
               const std::vector<float>* ka) {
  const size_t nv = mesh.positions.size();
  Json attributes = {{"POSITION", bin.attribute(mesh.positions, "VEC3", true)}};
  const bool own_normals = mesh.normals.size() == nv;
  if (normals) {
    SYLVA_CHECK(normals->size() == nv, "write_glb: normal count != vertex count");
    std::vector<glm::vec3> unit(nv);
    for (size_t v = 0; v < nv; ++v)
      unit[v] = unit_normal((*normals)[v], own_normals ? &mesh.normals[v] : nullptr);
    attributes["NORMAL"] = bin.attribute(unit, "VEC3");
  } else if (own_normals) {
    std::vector<glm::vec3> unit(nv);
    for (size_t v = 0; v < nv; ++v)
      unit[v] = unit_normal(mesh.normals[v], nullptr);
    attributes["NORMAL"] = bin.attribute(unit, "VEC3");
  }
  if (mesh.uvs.size() == nv) attributes["TEXCOORD_0"] = bin.attribute(mesh.uvs, "VEC2");
  const bool own_colors = mesh.colors.size() == nv;
  if (!ka && mesh.ka.size() == nv) ka = &mesh.ka;
  if (ka) {
    SYLVA_CHECK(ka->size() == nv, "write_glb: ka count != vertex count");
    std::vector<glm::vec3> preview(nv);
    for (size_t v = 0; v < nv; ++v) {
      const float k = (*ka)[v];
      SYLVA_CHECK(k >= 0.0f && k <= 1.0f, "write_glb: ka outside [0, 1]");
      preview[v] = own_colors ? glm::vec3(mesh.colors[v]) * k : glm::vec3(k);
    }
    attributes["COLOR_0"] = bin.attribute(preview, "VEC3");
    if (own_colors) attributes["COLOR_1"] = bin.attribute(mesh.colors, "VEC4");
    attributes["_AMBIENT"] = bin.attribute(*ka, "SCALAR");
  } else if (own_colors) {
    attributes["COLOR_0"] = bin.attribute(mesh.colors, "VEC4");
  }

  const size_t nt = mesh.triangle_count();
  const bool has_roles = mesh.roles.size() == nt;
  std::vector<Role> order;
  if (has_roles)
    for (Role r : mesh.roles)
      if (std::find(order.begin(), order.end(), r) == order.end()) order.push_back(r);
  if (order.empty()) order.push_back(Role::Other);

  Json primitives = Json::array();
  for (Role role : order) {
    std::vector<uint32_t> idx;
    uint32_t max_index = 0;
    for (size_t t = 0; t < nt; ++t) {
      if (has_roles && mesh.roles[t] != role) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = mesh.indices[3 * t + size_t(k)];
        SYLVA_CHECK(i < nv, "index out of range in write_glb");
        idx.push_back(i);
        max_index = std::max(max_index, i);
      }
    }
    Json prim = {{"attributes", attributes}, {"indices", bin.indices(idx, max_index)}, {"mode", 4}};
    if (mesh.material >= 0) prim["material"] = mesh.material;
    if (has_roles && order.size() > 1) prim["extras"] = {{"sylva_role", role_name(role)}};
    primitives.push_back(prim);
  }
  Json j = {{"name", mesh.name}, {"primitives", primitives}};
  if (has_roles && order.size() == 1) j["extras"]["sylva_role"] = role_name(order[0]);
  if (ka) j["extras"]["sylva_color_0"] = "ambient";
  if (normals || mesh.outward_normals) j["extras"]["sylva_normals"] = "outward";
  return j;
}

Json matrix_json(const glm::mat4& m) {
  Json out = Json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      out.push_back(m[c][r]);
  return out;
}

Json hierarchy_json(const Hierarchy& h) {
  return {{"branch_parent", h.branch_parent},
          {"branch_diameter", h.branch_diameter},
          {"leaf_branch", h.leaf_branch}};
}

// An instanced scene: a node per instance (its transform as "matrix", extras "sylva_plant" =
// the plant's name, so it reads back as that plant even when placed once), with a child node per
// plant mesh sharing the plant's glTF meshes. The plant's hierarchy rides on its first instance's
// node.
void instance_nodes(const Scene& scene, const std::vector<int>& mesh_index, Json& nodes,
                    Json& roots) {
  std::vector<char> first(scene.plants.size(), 1);
  for (const Instance& inst : scene.instances) {
    const Plant& plant = scene.plants[inst.plant];
    Json children = Json::array();
    for (uint32_t m : plant.meshes) {
      if (mesh_index[m] < 0) continue;
      nodes.push_back({{"name", scene.meshes[m].name}, {"mesh", mesh_index[m]}});
      children.push_back(nodes.size() - 1);
    }
    Json node = {{"name", inst.name.empty() ? plant.name : inst.name},
                 {"extras", {{"sylva_plant", plant.name.empty() ? Json(true) : Json(plant.name)}}}};
    if (inst.transform != glm::mat4(1.0f)) node["matrix"] = matrix_json(inst.transform);
    if (!children.empty()) node["children"] = children;
    if (first[inst.plant] && !plant.hierarchy.empty())
      node["extras"]["sylva_hierarchy"] = hierarchy_json(plant.hierarchy);
    first[inst.plant] = 0;
    nodes.push_back(node);
    roots.push_back(nodes.size() - 1);
  }
}

// Scene::cameras as glTF cameras, each placed by a root node of its name; returns the cameras.
Json camera_nodes(const Scene& scene, Json& nodes, Json& roots) {
  Json cameras = Json::array();
  for (const SceneCamera& c : scene.cameras) {
    Json cam;
    if (c.orthographic) {
      cam = {{"type", "orthographic"},
             {"orthographic",
              {{"xmag", c.xmag}, {"ymag", c.ymag}, {"znear", c.znear}, {"zfar", c.zfar}}}};
    } else {
      Json p = {{"yfov", c.yfov}, {"znear", c.znear}};
      if (c.aspect > 0.0f) p["aspectRatio"] = c.aspect;
      if (c.zfar > 0.0f) p["zfar"] = c.zfar;
      cam = {{"type", "perspective"}, {"perspective", p}};
    }
    cameras.push_back(cam);
    nodes.push_back(
        {{"name", c.name}, {"camera", cameras.size() - 1}, {"matrix", matrix_json(c.to_world)}});
    roots.push_back(nodes.size() - 1);
  }
  return cameras;
}

}  // namespace

void write_glb(const Scene& scene, const std::string& path, const GlbVertexData* extra) {
  const size_t n = scene.meshes.size();
  const bool new_normals = extra && !extra->normals.empty();
  const bool new_ka = extra && !extra->ka.empty();
  SYLVA_CHECK(!new_normals || extra->normals.size() == n, "write_glb: normals per mesh != meshes");
  SYLVA_CHECK(!new_ka || extra->ka.size() == n, "write_glb: ka per mesh != meshes");
  BinBuilder bin;
  Json gltf = {{"asset", {{"version", "2.0"}, {"generator", "sylva"}}}};
  Json meshes = Json::array(), nodes = Json::array(), node_ids = Json::array();
  std::vector<int> mesh_index(n, -1);  // glTF mesh of each scene mesh
  for (size_t m = 0; m < n; ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (mesh.positions.empty() || mesh.indices.size() < 3) continue;
    meshes.push_back(mesh_json(mesh, bin, new_normals ? &extra->normals[m] : nullptr,
                               new_ka ? &extra->ka[m] : nullptr));
    mesh_index[m] = int(meshes.size() - 1);
    if (scene.instanced()) continue;
    nodes.push_back({{"name", mesh.name}, {"mesh", meshes.size() - 1}});
    node_ids.push_back(nodes.size() - 1);
  }
  if (scene.instanced()) instance_nodes(scene, mesh_index, nodes, node_ids);
  Json cameras = camera_nodes(scene, nodes, node_ids);
  Json scene_json = {{"name", "sylva"}};
  if (!node_ids.empty()) scene_json["nodes"] = node_ids;
  if (!scene.hierarchy.empty() || !scene.hierarchy.leaf_branch.empty())
    scene_json["extras"]["sylva_hierarchy"] = hierarchy_json(scene.hierarchy);
  if (extra && !extra->note_json.empty()) {
    Json note = Json::parse(extra->note_json, nullptr, false);
    SYLVA_CHECK(note.is_object(), "write_glb: note_json must be a JSON object");
    scene_json["extras"]["sylva_baked"] = note;
  }
  gltf["scene"] = 0;
  gltf["scenes"] = Json::array({scene_json});
  if (!nodes.empty()) gltf["nodes"] = nodes;
  if (!meshes.empty()) gltf["meshes"] = meshes;
  if (!cameras.empty()) gltf["cameras"] = cameras;
  if (!scene.materials.empty()) {
    Json mats = Json::array();
    for (const Material& m : scene.materials)
      mats.push_back(material_json(m));
    gltf["materials"] = mats;
  }
  if (!scene.textures.empty()) {
    Json images = Json::array(), textures = Json::array();
    for (size_t t = 0; t < scene.textures.size(); ++t) {
      const std::string png = encode_png(scene.textures[t], path);
      Json image = {{"bufferView", bin.view(png.data(), png.size(), 0)}, {"mimeType", "image/png"}};
      if (!scene.textures[t].name.empty()) image["name"] = scene.textures[t].name;
      images.push_back(image);
      textures.push_back({{"sampler", 0}, {"source", t}});
    }
    gltf["images"] = images;
    gltf["textures"] = textures;
    gltf["samplers"] = Json::array(
        {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}});
  }
  while (bin.bin().size() % 4)
    bin.bin().push_back('\0');
  if (!bin.bin().empty()) {
    gltf["buffers"] = Json::array({{{"byteLength", bin.bin().size()}}});
    gltf["bufferViews"] = bin.views();
    gltf["accessors"] = bin.accessors();
  }

  const std::string glb = glb_assemble(gltf.dump(), bin.bin());
  write_file_atomic(path, glb);
}

}  // namespace sylva
