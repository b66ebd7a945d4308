#include "core/scene/gltf_nodes.h"

#include <array>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <tuple>

#include "core/error.h"

namespace sylva {

namespace {

using Json = nlohmann::json;

// A subtree's shape: its root's mesh, and each child's shape under its exact local matrix.
// Two nodes with the same key hold the same meshes at the same relative transforms.
using ChildKey = std::pair<int, std::array<double, 16>>;
using NodeKey = std::tuple<int, int, std::vector<ChildKey>>;  // mesh, EXT node (or -1), children

std::array<double, 16> matrix_bits(const glm::dmat4& m) {
  std::array<double, 16> a{};
  for (int i = 0; i < 16; ++i)
    a[size_t(i)] = m[i / 4][i % 4];
  return a;
}

size_t primitive_triangles(const tinygltf::Model& model, const tinygltf::Primitive& prim) {
  auto count = [&](int accessor) -> size_t {
    return accessor >= 0 && size_t(accessor) < model.accessors.size()
               ? model.accessors[size_t(accessor)].count
               : 0;
  };
  auto pos = prim.attributes.find("POSITION");
  const size_t n = prim.indices >= 0              ? count(prim.indices)
                   : pos != prim.attributes.end() ? count(pos->second)
                                                  : 0;
  if (prim.mode == TINYGLTF_MODE_TRIANGLES) return n / 3;
  if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP || prim.mode == TINYGLTF_MODE_TRIANGLE_FAN)
    return n > 2 ? n - 2 : 0;
  return 0;
}

class NodePlanner {
 public:
  NodePlanner(const std::string& path, const tinygltf::Model& model, const Json& json,
              const GltfAccessorReader& accessors)
      : m_path(path), m_model(model), m_json(json), m_accessors(accessors) {}

  NodePlan plan() {
    link_nodes();
    walk_world();
    shape_keys();
    m_plan.plants.push_back({"scene", -1, {}});
    place();
    return std::move(m_plan);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(m_path, what); }

  const tinygltf::Node& node(int i) const { return m_model.nodes[size_t(i)]; }

  // Parents, and the roots of the default scene (every parentless node without scenes).
  void link_nodes() {
    const size_t n = m_model.nodes.size();
    m_parent.assign(n, -1);
    for (size_t i = 0; i < n; ++i)
      for (int c : m_model.nodes[i].children) {
        if (c < 0 || size_t(c) >= n)
          fail("node " + std::to_string(i) + " has a missing child " + std::to_string(c));
        if (m_parent[size_t(c)] != -1 || size_t(c) == i)
          fail("node " + std::to_string(c) + " has more than one parent (glTF needs a tree)");
        m_parent[size_t(c)] = int(i);
      }
    const int s =
        m_model.defaultScene >= 0 ? m_model.defaultScene : (m_model.scenes.empty() ? -1 : 0);
    if (s >= int(m_model.scenes.size()))
      fail("the default scene " + std::to_string(s) + " does not exist");
    if (s >= 0) {
      m_roots = m_model.scenes[size_t(s)].nodes;
      for (int r : m_roots) {
        if (r < 0 || size_t(r) >= n)
          fail("scene " + std::to_string(s) + " refers to a missing node");
        if (m_parent[size_t(r)] != -1)
          fail("scene root node " + std::to_string(r) + " has a parent");
      }
    } else {
      for (size_t i = 0; i < n; ++i)
        if (m_parent[i] == -1) m_roots.push_back(int(i));
    }
  }

  // Pre-order over the scene (iterative: deep chains cannot overflow the stack), with each
  // node's world matrix. One parent per node and parentless roots: no cycle.
  void walk_world() {
    const size_t n = m_model.nodes.size();
    m_world.assign(n, glm::dmat4(1.0));
    std::vector<char> seen(n, 0);
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = m_roots.rbegin(); it != m_roots.rend(); ++it)
      stack.emplace_back(*it, glm::dmat4(1.0));
    while (!stack.empty()) {
      auto [i, parent_world] = stack.back();
      stack.pop_back();
      if (seen[size_t(i)]) fail("node " + std::to_string(i) + " appears twice in the scene");
      seen[size_t(i)] = 1;
      m_order.push_back(i);
      m_world[size_t(i)] = parent_world * node_matrix(node(i));
      const tinygltf::Node& nd = node(i);
      if (nd.mesh >= 0 && size_t(nd.mesh) >= m_model.meshes.size())
        fail("node '" + nd.name + "' refers to a missing mesh");
      if (nd.camera >= 0 && size_t(nd.camera) >= m_model.cameras.size())
        fail("node '" + nd.name + "' refers to a missing camera");
      for (auto c = nd.children.rbegin(); c != nd.children.rend(); ++c)
        stack.emplace_back(*c, m_world[size_t(i)]);
    }
  }

  // Node i's raw JSON object, or null.
  const Json* node_json(int i) const {
    if (!m_json.contains("nodes")) return nullptr;
    const Json& nodes = m_json["nodes"];
    if (!nodes.is_array() || size_t(i) >= nodes.size() || !nodes[size_t(i)].is_object())
      return nullptr;
    return &nodes[size_t(i)];
  }

  const Json* ext_of(int i) const {
    const Json* j = node_json(i);
    if (!j) return nullptr;
    const Json& nd = *j;
    if (!nd.is_object() || !nd.contains("extensions") || !nd["extensions"].is_object() ||
        !nd["extensions"].contains("EXT_mesh_gpu_instancing"))
      return nullptr;
    return &nd["extensions"]["EXT_mesh_gpu_instancing"];
  }

  // extras "sylva_plant": true, or the plant's name.
  const Json* plant_marker(int i) const {
    const Json* j = node_json(i);
    if (!j) return nullptr;
    const Json& nd = *j;
    if (!nd.contains("extras") || !nd["extras"].is_object() ||
        !nd["extras"].contains("sylva_plant"))
      return nullptr;
    const Json& m = nd["extras"]["sylva_plant"];
    return m == true || (m.is_string() && !m.get<std::string>().empty()) ? &m : nullptr;
  }

  size_t mesh_triangles(int mesh) const {
    if (mesh < 0) return 0;
    size_t n = 0;
    for (const tinygltf::Primitive& p : m_model.meshes[size_t(mesh)].primitives)
      n += primitive_triangles(m_model, p);
    return n;
  }

  // Children before parents: each node's shape key and subtree triangle count.
  void shape_keys() {
    std::map<NodeKey, int> interned;
    m_key.assign(m_model.nodes.size(), -1);
    m_triangles.assign(m_model.nodes.size(), 0);
    for (auto it = m_order.rbegin(); it != m_order.rend(); ++it) {
      const int i = *it;
      const tinygltf::Node& nd = node(i);
      std::vector<ChildKey> children;
      size_t tris = mesh_triangles(nd.mesh);
      for (int c : nd.children) {
        children.emplace_back(m_key[size_t(c)], matrix_bits(node_matrix(node(c))));
        tris += m_triangles[size_t(c)];
      }
      NodeKey key{nd.mesh, ext_of(i) ? i : -1, std::move(children)};
      auto [at, added] = interned.emplace(std::move(key), int(interned.size()));
      m_key[size_t(i)] = at->second;
      m_triangles[size_t(i)] = tris;
    }
    m_key_count.assign(interned.size(), 0);
    for (int i : m_order)
      ++m_key_count[size_t(m_key[size_t(i)])];
  }

  bool plant_root(int i) const {
    if (m_triangles[size_t(i)] == 0) return false;
    if (plant_marker(i)) return true;
    return m_key_count[size_t(m_key[size_t(i)])] >= 2 &&
           m_triangles[size_t(i)] >= kMinPlantTriangles;
  }

  // The placements of node i's subtree relative to i (i's own matrix excluded), pre-order.
  std::vector<MeshPlacement> subtree_meshes(int root) {
    std::vector<MeshPlacement> out;
    std::vector<std::pair<int, glm::dmat4>> stack{{root, glm::dmat4(1.0)}};
    while (!stack.empty()) {
      auto [i, rel] = stack.back();
      stack.pop_back();
      place_node_mesh(i, rel, out);
      for (auto c = node(i).children.rbegin(); c != node(i).children.rend(); ++c)
        stack.emplace_back(*c, rel * node_matrix(node(*c)));
    }
    return out;
  }

  // Node i's mesh at `at` into `out`, once per EXT_mesh_gpu_instancing instance if it has any.
  void place_node_mesh(int i, const glm::dmat4& at, std::vector<MeshPlacement>& out) {
    const int mesh = node(i).mesh;
    if (mesh < 0) return;
    if (!ext_of(i)) {
      out.push_back({mesh, i, at});
      return;
    }
    for (const glm::dmat4& m : gpu_instances(i))
      out.push_back({mesh, i, at * m});
  }

  size_t plant_of(int key, int root, const std::string& name, std::vector<MeshPlacement> meshes) {
    auto it = m_plant_of_key.find(key);
    if (it != m_plant_of_key.end()) return it->second;
    PlantPlan p;
    p.root_node = root;
    p.name = !name.empty() ? name : "plant " + std::to_string(m_plan.plants.size());
    p.meshes = std::move(meshes);
    m_plan.plants.push_back(std::move(p));
    return m_plant_of_key[key] = m_plan.plants.size() - 1;
  }

  std::string mesh_name(int node_index) const {
    const tinygltf::Node& nd = node(node_index);
    if (nd.mesh >= 0 && !m_model.meshes[size_t(nd.mesh)].name.empty())
      return m_model.meshes[size_t(nd.mesh)].name;
    return nd.name;
  }

  // Top-down: a plant root becomes an instance (its subtree is the plant's, walked once per
  // shape); an instanced mesh of a plant's size becomes a plant with an instance per entry;
  // every other mesh goes to plants[0] in world space.
  void place() {
    std::vector<int> stack(m_roots.rbegin(), m_roots.rend());
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const tinygltf::Node& nd = node(i);
      if (nd.camera >= 0) m_plan.cameras.push_back({nd.camera, i, m_world[size_t(i)]});
      if (plant_root(i)) {
        const int key = m_key[size_t(i)];
        const Json* marker = plant_marker(i);
        const std::string name = marker && marker->is_string() ? marker->get<std::string>()
                                 : nd.name.empty()             ? mesh_name(i)
                                                               : nd.name;
        const bool known = m_plant_of_key.count(key) > 0;
        const size_t p =
            plant_of(key, i, name, known ? std::vector<MeshPlacement>{} : subtree_meshes(i));
        m_plan.instances.push_back({p, m_world[size_t(i)], nd.name});
        add_cameras_below(i);
        continue;
      }
      if (nd.mesh >= 0 && ext_of(i) && mesh_triangles(nd.mesh) >= kMinPlantTriangles) {
        const size_t p = plant_of(-1 - nd.mesh, -1, mesh_name(i), {{nd.mesh, i, glm::dmat4(1.0)}});
        const std::vector<glm::dmat4> entries = gpu_instances(i);
        for (size_t k = 0; k < entries.size(); ++k)
          m_plan.instances.push_back(
              {p, m_world[size_t(i)] * entries[k], nd.name + "#" + std::to_string(k)});
      } else {
        place_node_mesh(i, m_world[size_t(i)], m_plan.plants[0].meshes);
      }
      for (auto c = nd.children.rbegin(); c != nd.children.rend(); ++c)
        stack.push_back(*c);
    }
    if (m_plan.instances.size() > kMaxInstances)
      fail("too many instances: " + std::to_string(m_plan.instances.size()) + " (at most " +
           std::to_string(kMaxInstances) + ")");
  }

  void add_cameras_below(int root) {
    std::vector<int> stack(node(root).children.rbegin(), node(root).children.rend());
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      if (node(i).camera >= 0) m_plan.cameras.push_back({node(i).camera, i, m_world[size_t(i)]});
      for (auto c = node(i).children.rbegin(); c != node(i).children.rend(); ++c)
        stack.push_back(*c);
    }
  }

  // EXT_mesh_gpu_instancing: one matrix per instance, T * R * S from the TRANSLATION,
  // ROTATION and SCALE accessors (each optional, all of one count).
  std::vector<glm::dmat4> gpu_instances(int i) {
    auto cached = m_gpu_instances.find(i);
    if (cached != m_gpu_instances.end()) return cached->second;
    const std::string where = "node " + std::to_string(i) + " EXT_mesh_gpu_instancing";
    const Json* ext = ext_of(i);
    if (!ext->is_object() || !ext->contains("attributes") || !(*ext)["attributes"].is_object())
      fail(where + ": needs an attributes object");
    const Json& attributes = (*ext)["attributes"];
    std::vector<float> t, r, s;
    size_t count = 0;
    bool any = false;
    auto read = [&](const char* name, int comps, bool rotation, std::vector<float>& out) {
      if (!attributes.contains(name)) return;
      const Json& a = attributes[name];
      if (!a.is_number_integer() || a.get<long long>() < 0 ||
          size_t(a.get<long long>()) >= m_model.accessors.size())
        fail(where + ": " + name + " refers to a missing accessor");
      const int index = a.get<int>();
      check_instance_accessor(m_model.accessors[size_t(index)], where, name, comps, rotation);
      int got = 0;
      out = m_accessors.floats(index, got, name);
      const size_t n = out.size() / size_t(comps);
      if (any && n != count)
        fail(where + ": " + name + " has " + std::to_string(n) + " entries, the others " +
             std::to_string(count));
      count = n;
      any = true;
    };
    read("TRANSLATION", 3, false, t);
    read("ROTATION", 4, true, r);
    read("SCALE", 3, false, s);
    if (!any) fail(where + ": needs TRANSLATION, ROTATION or SCALE");
    if (count == 0) fail(where + ": has no instances (accessor count 0)");
    if (count > kMaxInstances)
      fail(where + ": too many instances: " + std::to_string(count) + " (at most " +
           std::to_string(kMaxInstances) + ")");
    std::vector<glm::dmat4> out(count, glm::dmat4(1.0));
    for (size_t k = 0; k < count; ++k) {
      glm::dmat4& m = out[k];
      if (!t.empty()) m = glm::translate(m, glm::dvec3(t[3 * k], t[3 * k + 1], t[3 * k + 2]));
      if (!r.empty()) {
        const glm::dquat q(r[4 * k + 3], r[4 * k], r[4 * k + 1], r[4 * k + 2]);
        if (!(glm::length(q) > 1e-6))
          fail(where + ": ROTATION " + std::to_string(k) + " is not a unit quaternion");
        m *= glm::mat4_cast(glm::normalize(q));
      }
      if (!s.empty()) m = glm::scale(m, glm::dvec3(s[3 * k], s[3 * k + 1], s[3 * k + 2]));
    }
    return m_gpu_instances[i] = out;
  }

  // The extension's rules: TRANSLATION and SCALE float VEC3; ROTATION VEC4 of floats or
  // normalized signed bytes or shorts.
  void check_instance_accessor(const tinygltf::Accessor& acc, const std::string& where,
                               const char* name, int comps, bool rotation) const {
    const bool type_ok = acc.type == (comps == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
    const int ct = acc.componentType;
    const bool component_ok =
        ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
        (rotation && acc.normalized &&
         (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT));
    if (!type_ok || !component_ok)
      fail(where + ": " + name + " must be a " + (comps == 3 ? "VEC3" : "VEC4") + " of floats" +
           (rotation ? " or normalized bytes/shorts" : ""));
  }

  const std::string& m_path;
  const tinygltf::Model& m_model;
  const Json& m_json;
  const GltfAccessorReader& m_accessors;
  std::vector<int> m_parent, m_roots, m_order, m_key;
  std::vector<glm::dmat4> m_world;
  std::vector<size_t> m_triangles, m_key_count;
  std::map<int, size_t> m_plant_of_key;  // shape key, or -1 - mesh for instanced meshes
  std::map<int, std::vector<glm::dmat4>> m_gpu_instances;
  NodePlan m_plan;
};

}  // namespace

glm::dmat4 node_matrix(const tinygltf::Node& node) {
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

NodePlan plan_nodes(const std::string& path, const tinygltf::Model& model, const Json& json,
                    const GltfAccessorReader& accessors) {
  return NodePlanner(path, model, json, accessors).plan();
}

}  // namespace sylva
