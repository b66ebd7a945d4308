#include "core/scene/scene.h"

#include "core/scene/instances.h"
#include "core/scene/point_tree.h"

#include <algorithm>
#include <cmath>

namespace sylva {

const char* role_name(Role r) {
  switch (r) {
    case Role::Foliage:
      return "foliage";
    case Role::Wood:
      return "wood";
    case Role::Ground:
      return "ground";
    case Role::Other:
      return "other";
    case Role::Grass:
      return "grass";
  }
  return "other";
}

const char* alpha_mode_name(AlphaMode m) {
  switch (m) {
    case AlphaMode::Opaque:
      return "OPAQUE";
    case AlphaMode::Mask:
      return "MASK";
    case AlphaMode::Blend:
      return "BLEND";
  }
  return "OPAQUE";
}

void SceneReport::warn(const std::string& kind, const std::string& text) {
  for (Kind& k : m_kinds)
    if (k.name == kind) {
      ++k.repeats;
      return;
    }
  m_kinds.push_back({kind, warnings.size(), 0});
  warnings.push_back(text);
}

std::vector<std::string> SceneReport::warning_lines() const {
  std::vector<std::string> out = warnings;
  for (const Kind& k : m_kinds)
    if (k.repeats > 0 && k.line < out.size())
      out[k.line] += " (and " + std::to_string(k.repeats) + " more like it)";
  return out;
}

namespace {

// The vertices of the triangles passing keep(mesh, t) in `meshes`, each once, in mesh and
// vertex order.
template <class Keep>
std::vector<glm::vec3> used_points(const Scene& scene, const std::vector<uint32_t>& meshes,
                                   Keep keep) {
  std::vector<glm::vec3> points;
  for (uint32_t mi : meshes) {
    const Mesh& m = scene.meshes[mi];
    std::vector<char> used(m.positions.size(), 0);
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (keep(m, t))
        for (int k = 0; k < 3; ++k)
          used[m.indices[3 * t + size_t(k)]] = 1;
    for (size_t v = 0; v < used.size(); ++v)
      if (used[v]) points.push_back(m.positions[v]);
  }
  return points;
}

std::vector<uint32_t> all_meshes(const Scene& scene) {
  std::vector<uint32_t> all(scene.meshes.size());
  for (size_t m = 0; m < all.size(); ++m)
    all[m] = uint32_t(m);
  return all;
}

// Per plant, a tree of the vertices passing `keep` (an instanced scene).
template <class Keep>
std::vector<PointTree> plant_trees(const Scene& scene, Keep keep) {
  std::vector<PointTree> trees;
  for (const Plant& plant : scene.plants)
    trees.emplace_back(used_points(scene, plant.meshes, keep));
  return trees;
}

// The world bounds of the vertices passing `keep`: stored positions in a flat scene, every
// instance's moved in double as the glTF reader flattens nodes (exactly, core/scene/
// point_tree.h).
template <class Keep>
Bounds world_bounds(const Scene& scene, Keep keep) {
  Bounds b;
  if (!scene.instanced()) {
    for (const glm::vec3& p : used_points(scene, all_meshes(scene), keep))
      b.extend(p);
    return b;
  }
  const std::vector<PointTree> trees = plant_trees(scene, keep);
  for (const Instance& inst : scene.instances) {
    const Bounds i = trees[inst.plant].moved_bounds(glm::dmat4(inst.transform));
    if (!i.empty()) b.extend(i.min), b.extend(i.max);
  }
  return b;
}

// The largest squared distance from c of the vertices passing `keep`, moved as above.
template <class Keep>
float world_max_distance2(const Scene& scene, Keep keep, const glm::vec3& c) {
  float r2 = 0.0f;
  if (!scene.instanced()) {
    for (const glm::vec3& p : used_points(scene, all_meshes(scene), keep)) {
      const glm::vec3 d = p - c;
      r2 = std::max(r2, glm::dot(d, d));
    }
    return r2;
  }
  const std::vector<PointTree> trees = plant_trees(scene, keep);
  for (const Instance& inst : scene.instances)
    r2 = std::max(r2, trees[inst.plant].max_distance2(glm::dmat4(inst.transform), c));
  return r2;
}

}  // namespace

Bounds Scene::bounds() const {
  return world_bounds(*this, [](const Mesh&, size_t) { return true; });
}

Sphere Scene::framing_sphere() const {
  // Triangles without a role count as framed (Role::Other).
  bool skip_ground = false;
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.triangle_count() && !skip_ground; ++t)
      skip_ground = t < m.roles.size() && m.roles[t] != Role::Ground;
  if (!skip_ground)
    for (const Mesh& m : meshes)
      skip_ground = skip_ground || (m.roles.empty() && !m.indices.empty());
  auto framed = [skip_ground](const Mesh& m, size_t t) {
    return !skip_ground || t >= m.roles.size() || m.roles[t] != Role::Ground;
  };
  const Bounds b = world_bounds(*this, framed);
  Sphere s;
  if (b.empty()) return s;
  s.centre = b.center();
  s.radius = std::sqrt(world_max_distance2(*this, framed, s.centre));
  return s;
}

Bounds Scene::bounds(Role role) const {
  return world_bounds(*this, [role](const Mesh& m, size_t t) { return m.roles[t] == role; });
}

Bounds Scene::bounds_except(Role role) const {
  return world_bounds(
      *this, [role](const Mesh& m, size_t t) { return t >= m.roles.size() || m.roles[t] != role; });
}

size_t Scene::drawn_triangle_count() const {
  if (!instanced()) return triangle_count();
  size_t n = 0;
  for (const Instance& inst : instances)
    for (uint32_t mi : plants[inst.plant].meshes)
      n += meshes[mi].triangle_count();
  return n;
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes)
    n += m.triangle_count();
  return n;
}

size_t Scene::vertex_count() const {
  size_t n = 0;
  for (const Mesh& m : meshes)
    n += m.positions.size();
  return n;
}

uint32_t Scene::max_primitive_id() const {
  uint32_t n = 0;
  for (const Mesh& m : meshes)
    for (uint32_t id : m.primitive_ids)
      n = std::max(n, id);
  return n;
}

uint32_t Scene::max_cluster_id() const {
  uint32_t n = 0;
  for (const Mesh& m : meshes)
    for (uint32_t id : m.cluster_ids)
      n = std::max(n, id);
  return n;
}

uint32_t Scene::branch_cluster_id() const {
  if (instanced()) return id_layout(*this).branch_cluster;
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.roles.size() && t < m.cluster_ids.size(); ++t)
      if (m.roles[t] != Role::Foliage) return m.cluster_ids[t];
  return 0;
}

}  // namespace sylva
