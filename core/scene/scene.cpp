#include "core/scene/scene.h"

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

Bounds Scene::bounds() const {
  Bounds b;
  for (const Mesh& m : meshes)
    for (uint32_t i : m.indices)
      b.extend(m.positions[i]);
  return b;
}

Sphere Scene::framing_sphere() const {
  // Triangles without a role count as framed (Role::Other).
  auto framed = [](const Mesh& m, size_t t, bool skip_ground) {
    return !skip_ground || t >= m.roles.size() || m.roles[t] != Role::Ground;
  };
  bool skip_ground = false;
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.triangle_count() && !skip_ground; ++t)
      skip_ground = t < m.roles.size() && m.roles[t] != Role::Ground;
  if (!skip_ground)
    for (const Mesh& m : meshes)
      skip_ground = skip_ground || (m.roles.empty() && !m.indices.empty());
  Bounds b;
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (framed(m, t, skip_ground))
        for (int k = 0; k < 3; ++k)
          b.extend(m.positions[m.indices[3 * t + size_t(k)]]);
  Sphere s;
  if (b.empty()) return s;
  s.centre = b.center();
  float r2 = 0.0f;
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (framed(m, t, skip_ground))
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 d = m.positions[m.indices[3 * t + size_t(k)]] - s.centre;
          r2 = std::max(r2, glm::dot(d, d));
        }
  s.radius = std::sqrt(r2);
  return s;
}

Bounds Scene::bounds(Role role) const {
  Bounds b;
  for (const Mesh& m : meshes) {
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (m.roles[t] != role) continue;
      for (int k = 0; k < 3; ++k)
        b.extend(m.positions[m.indices[3 * t + k]]);
    }
  }
  return b;
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
  for (const Mesh& m : meshes)
    for (size_t t = 0; t < m.roles.size() && t < m.cluster_ids.size(); ++t)
      if (m.roles[t] != Role::Foliage) return m.cluster_ids[t];
  return 0;
}

}  // namespace sylva
