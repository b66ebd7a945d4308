#include "core/scene/gltf_primitives.h"

#include <cmath>
#include <variant>

#include "core/error.h"
#include "core/scene/load.h"

namespace sylva {

namespace {

using Json = nlohmann::json;

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

bool marked(const Json* j, const char* value) {
  return j && j->is_string() && *j == value;
}

// Reads one primitive of one mesh; the reader's state is its arguments.
class PrimitiveRead {
 public:
  PrimitiveRead(const std::string& path, const GltfAccessorReader& accessors,
                const tinygltf::Primitive& prim, std::string where, SceneReport& report)
      : m_path(path),
        m_accessors(accessors),
        m_prim(prim),
        m_where(std::move(where)),
        m_report(report) {}

  void vertices(Mesh& mesh) {
    int comps = 0;
    std::vector<float> p = m_accessors.floats(attribute("POSITION"), comps, "POSITION");
    if (comps != 3) fail("POSITION must be VEC3");
    m_nv = p.size() / 3;
    mesh.positions.resize(m_nv);
    for (size_t v = 0; v < m_nv; ++v)
      mesh.positions[v] = glm::vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
    if (has("NORMAL")) {
      std::vector<float> n = m_accessors.floats(attribute("NORMAL"), comps, "NORMAL");
      if (comps != 3 || n.size() != p.size()) fail("NORMAL must be VEC3 with one per vertex");
      mesh.normals.resize(m_nv);
      for (size_t v = 0; v < m_nv; ++v)
        mesh.normals[v] = glm::vec3(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
    }
    if (has("TEXCOORD_0")) {
      std::vector<float> uv = m_accessors.floats(attribute("TEXCOORD_0"), comps, "TEXCOORD_0");
      if (comps != 2 || uv.size() != m_nv * 2) fail("TEXCOORD_0 must be VEC2 with one per vertex");
      mesh.uvs.resize(m_nv);
      for (size_t v = 0; v < m_nv; ++v)
        mesh.uvs[v] = glm::vec2(uv[2 * v], uv[2 * v + 1]);
    }
  }

  // A baked file's COLOR_0 is the ka preview for other engines (gltf_write.h); its real
  // vertex colours, if any, are in COLOR_1.
  void colors(Mesh& mesh, bool baked_colors) {
    const char* name = baked_colors ? "COLOR_1" : "COLOR_0";
    if (!has(name)) return;
    int comps = 0;
    std::vector<float> c = m_accessors.floats(attribute(name), comps, name);
    if ((comps != 3 && comps != 4) || c.size() != m_nv * size_t(comps))
      fail(std::string(name) + " must be VEC3 or VEC4 with one per vertex");
    mesh.colors.resize(m_nv);
    for (size_t v = 0; v < m_nv; ++v)
      mesh.colors[v] = glm::vec4(c[comps * v], c[comps * v + 1], c[comps * v + 2],
                                 comps == 4 ? c[comps * v + 3] : 1.0f);
  }

  void ambient(Mesh& mesh) {
    if (!has("_AMBIENT")) return;
    int comps = 0;
    mesh.ka = m_accessors.floats(attribute("_AMBIENT"), comps, "_AMBIENT");
    if (comps != 1 || mesh.ka.size() != m_nv) fail("_AMBIENT must be SCALAR with one per vertex");
    for (size_t v = 0; v < m_nv; ++v)
      if (!(mesh.ka[v] >= 0.0f && mesh.ka[v] <= 1.0f))
        fail("_AMBIENT (ambient coefficient) " + std::to_string(mesh.ka[v]) + " at vertex " +
             std::to_string(v) + " is outside [0, 1]");
  }

  void triangles(Mesh& mesh) {
    std::vector<uint32_t> idx;
    if (m_prim.indices >= 0) {
      idx = m_accessors.indices(m_prim.indices);
    } else {
      idx.resize(m_nv);
      for (size_t v = 0; v < m_nv; ++v)
        idx[v] = uint32_t(v);
    }
    for (uint32_t i : idx)
      if (i >= m_nv)
        fail("vertex index " + std::to_string(i) + " out of range (" + std::to_string(m_nv) +
             " vertices)");
    mesh.indices = triangulate(idx);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(m_path, m_where + ": " + what);
  }
  bool has(const char* name) const { return m_prim.attributes.count(name) > 0; }
  int attribute(const char* name) const { return m_prim.attributes.at(name); }

  std::vector<uint32_t> triangulate(const std::vector<uint32_t>& idx) {
    if (m_prim.mode == TINYGLTF_MODE_TRIANGLES) {
      if (idx.size() % 3 != 0)
        m_report.warn("index count",
                      m_where + ": index count not a multiple of 3, extra indices ignored");
      return std::vector<uint32_t>(idx.begin(), idx.begin() + long(idx.size() / 3 * 3));
    }
    std::vector<uint32_t> out;
    for (size_t i = 0; i + 2 < idx.size(); ++i) {
      if (m_prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP)  // glTF 2.0 §3.7.2.1: odd ones swap
        out.insert(out.end(), {idx[i], idx[i + 1 + i % 2], idx[i + 2 - i % 2]});
      else
        out.insert(out.end(), {idx[i + 1], idx[i + 2], idx[0]});
    }
    return out;
  }

  const std::string& m_path;
  const GltfAccessorReader& m_accessors;
  const tinygltf::Primitive& m_prim;
  std::string m_where;
  SceneReport& m_report;
  size_t m_nv = 0;
};

}  // namespace

GltfPrimitiveReader::GltfPrimitiveReader(const std::string& path, const tinygltf::Model& model,
                                         const Json& json, const GltfAccessorReader& accessors,
                                         size_t material_count, SceneReport& report)
    : m_path(path),
      m_model(model),
      m_json(json),
      m_accessors(accessors),
      m_material_count(material_count),
      m_report(report) {}

std::string GltfPrimitiveReader::name(int mesh, const std::string& node_name,
                                      const LocalPrimitive& p) const {
  const tinygltf::Mesh& src = m_model.meshes[size_t(mesh)];
  std::string name = !src.name.empty()    ? src.name
                     : !node_name.empty() ? node_name
                                          : "mesh" + std::to_string(mesh);
  // Appended, not "+": "[" + std::string&& trips a GCC 12 -Wrestrict false positive.
  return name.append(p.mesh.name);
}

const std::vector<LocalPrimitive>& GltfPrimitiveReader::read(int mesh_index,
                                                             const std::string& node_name) {
  auto known = m_read.find(mesh_index);
  if (known != m_read.end()) return known->second;
  const tinygltf::Mesh& src = m_model.meshes[size_t(mesh_index)];
  const size_t m = size_t(mesh_index);
  const Json* jmesh = json_at(m_json, {"meshes", m});
  const bool baked_colors =
      marked(json_at(m_json, {"meshes", m, "extras", "sylva_color_0"}), "ambient");
  const bool outward = marked(json_at(m_json, {"meshes", m, "extras", "sylva_normals"}), "outward");
  std::vector<LocalPrimitive> out;
  for (size_t k = 0; k < src.primitives.size(); ++k) {
    const tinygltf::Primitive& prim = src.primitives[k];
    LocalPrimitive lp;
    if (src.primitives.size() > 1) lp.mesh.name.append("[").append(std::to_string(k)).append("]");
    const std::string name = this->name(mesh_index, node_name, lp);
    if (prim.mode >= 0 && prim.mode <= 3) {
      m_report.warn("points/lines", "mesh '" + name + "': points/lines primitive skipped");
      continue;
    }
    if (prim.mode < 0 || prim.mode > 6)
      throw InputError(m_path,
                       "mesh '" + name + "': unknown primitive mode " + std::to_string(prim.mode));
    if (!prim.attributes.count("POSITION")) {
      m_report.warn("no POSITION", "mesh '" + name + "': primitive without POSITION skipped");
      continue;
    }
    Mesh& mesh = lp.mesh;
    mesh.material = prim.material;
    if (prim.material >= int(m_material_count) || prim.material < -1)
      throw InputError(m_path, "mesh '" + name + "': material does not exist");
    PrimitiveRead r(m_path, m_accessors, prim, "mesh '" + name + "'", m_report);
    r.vertices(mesh);
    mesh.outward_normals = outward;
    r.colors(mesh, baked_colors);
    r.ambient(mesh);
    r.triangles(mesh);
    bool found = false;
    Role role = Role::Other;
    if (const Json* jp = json_at(m_json, {"meshes", m, "primitives", k, "extras"}))
      role = parse_role(*jp, found);
    if (!found && jmesh && jmesh->contains("extras")) role = parse_role((*jmesh)["extras"], found);
    if (found) mesh.roles.assign(mesh.triangle_count(), role);
    if (!mesh.indices.empty()) out.push_back(std::move(lp));
  }
  return m_read[mesh_index] = std::move(out);
}

Mesh place_primitive(const LocalPrimitive& p, const glm::dmat4& transform, std::string name) {
  Mesh mesh = p.mesh;
  mesh.name = std::move(name);
  for (glm::vec3& q : mesh.positions)
    q = glm::vec3(transform * glm::dvec4(q.x, q.y, q.z, 1.0));
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
  for (glm::vec3& n : mesh.normals) {
    const glm::dvec3 wn = normal_matrix * glm::dvec3(n.x, n.y, n.z);
    const double len = glm::length(wn);
    n = len > 0.0 && std::isfinite(len) ? glm::vec3(wn / len) : glm::vec3(0.0f);
  }
  if (glm::determinant(glm::dmat3(transform)) < 0.0)
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  if (mesh.normals.empty()) compute_vertex_normals(mesh);
  return mesh;
}

const Json* json_at(const Json& root,
                    std::initializer_list<std::variant<const char*, size_t>> keys) {
  const Json* j = &root;
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

}  // namespace sylva
