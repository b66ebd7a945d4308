#include "core/scene/scene.h"

#include "core/scene/instances.h"

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

// Calls fn(world position) for every vertex of a triangle passing keep(mesh, t), once per
// instance of its plant. A flat scene's positions are passed as stored (no arithmetic); an
// instance's go through the transform in double, as the glTF reader flattens nodes.
template <class Keep, class Fn>
void for_each_world_vertex(const Scene& scene, Keep keep, Fn fn) {
  auto used = [&](const Mesh& m) {
    std::vector<char> u(m.positions.size(), 0);
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (keep(m, t))
        for (int k = 0; k < 3; ++k)
          u[m.indices[3 * t + size_t(k)]] = 1;
    return u;
  };
  if (!scene.instanced()) {
    for (const Mesh& m : scene.meshes) {
      const std::vector<char> u = used(m);
      for (size_t v = 0; v < u.size(); ++v)
        if (u[v]) fn(m.positions[v]);
    }
    return;
  }
  for (const Plant& plant : scene.plants) {
    std::vector<glm::vec3> points;
    for (uint32_t mi : plant.meshes) {
      const Mesh& m = scene.meshes[mi];
      const std::vector<char> u = used(m);
      for (size_t v = 0; v < u.size(); ++v)
        if (u[v]) points.push_back(m.positions[v]);
    }
    const auto p = uint32_t(&plant - scene.plants.data());
    for (const Instance& inst : scene.instances) {
      if (inst.plant != p) continue;
      const glm::dmat4 t(inst.transform);
      for (const glm::vec3& q : points)
        fn(glm::vec3(t * glm::dvec4(q, 1.0)));
    }
  }
}

}  // namespace

Bounds Scene::bounds() const {
  Bounds b;
  for_each_world_vertex(
      *this, [](const Mesh&, size_t) { return true; }, [&](const glm::vec3& p) { b.extend(p); });
  return b;
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
  Bounds b;
  for_each_world_vertex(*this, framed, [&](const glm::vec3& p) { b.extend(p); });
  Sphere s;
  if (b.empty()) return s;
  s.centre = b.center();
  float r2 = 0.0f;
  for_each_world_vertex(*this, framed, [&](const glm::vec3& p) {
    const glm::vec3 d = p - s.centre;
    r2 = std::max(r2, glm::dot(d, d));
  });
  s.radius = std::sqrt(r2);
  return s;
}

Bounds Scene::bounds(Role role) const {
  Bounds b;
  for_each_world_vertex(
      *this, [role](const Mesh& m, size_t t) { return m.roles[t] == role; },
      [&](const glm::vec3& p) { b.extend(p); });
  return b;
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
