// Scene builders and small helpers for the raster tests: analytic meshes (UV spheres, quads)
// with every per-triangle array filled, a process-wide GL context, request shorthands.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "core/gl/rasterizer.h"

namespace sylva::test {

inline GlContext& gl() {
  static std::unique_ptr<GlContext> context = create_gl_context();
  return *context;
}

// Fills the per-triangle arrays with one primitive / cluster id and role.
inline void set_ids(Mesh& m, uint32_t primitive, uint32_t cluster, Role role = Role::Foliage) {
  const size_t n = m.triangle_count();
  m.primitive_ids.assign(n, primitive);
  m.cluster_ids.assign(n, cluster);
  m.roles.assign(n, role);
}

// Appends a UV sphere as its own connected component, triangles wound CCW from outside.
inline void add_sphere(Mesh& m, glm::vec3 centre, float radius, int seg_u, int seg_v,
                       float normal_length = 1.0f) {
  const auto base = static_cast<uint32_t>(m.positions.size());
  for (int j = 0; j <= seg_v; ++j) {
    const float theta = std::numbers::pi_v<float> * j / seg_v;
    for (int i = 0; i <= seg_u; ++i) {
      const float phi = 2.0f * std::numbers::pi_v<float> * i / seg_u;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        -std::sin(theta) * std::sin(phi));
      m.positions.push_back(centre + radius * n);
      m.normals.push_back(normal_length * n);
      m.uvs.emplace_back(static_cast<float>(i) / seg_u, static_cast<float>(j) / seg_v);
    }
  }
  auto at = [&](int i, int j) { return base + static_cast<uint32_t>(j * (seg_u + 1) + i); };
  for (int j = 0; j < seg_v; ++j) {
    for (int i = 0; i < seg_u; ++i) {
      if (j != 0) m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)});
      if (j != seg_v - 1) {
        m.indices.insert(m.indices.end(), {at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
      }
    }
  }
}

// A quad in the z = z0 plane facing +Z (CCW seen from +Z), uv (0, 0) at the top left.
inline Mesh make_quad(float half, float z0, float normal_length = 1.0f) {
  Mesh m;
  m.name = "quad";
  m.positions = {{-half, -half, z0}, {half, -half, z0}, {half, half, z0}, {-half, half, z0}};
  m.normals.assign(4, glm::vec3(0, 0, normal_length));
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

inline Scene scene_of(std::vector<Mesh> meshes, Material material = {}) {
  Scene s;
  s.materials.push_back(material);
  for (Mesh& m : meshes)
    m.material = 0;
  s.meshes = std::move(meshes);
  return s;
}

inline Camera front_camera(const Scene& s, int size, bool ortho = false, float az = 0.0f,
                           float distance = 0.0f) {
  OrbitParams p;
  p.azimuth_deg = az;
  p.elevation_deg = 0.0f;
  p.ortho = ortho;
  p.distance = distance;
  return make_orbit_camera(s.bounds(), p, size, size);
}

inline Lighting ambient_only(float ambient) {
  Lighting l;
  l.ambient = ambient;
  return l;
}

inline RasterRequest request_of(TargetMask targets, IdKind kind = IdKind::Primitive, int ssaa = 1) {
  RasterRequest r;
  r.targets = targets;
  r.id_kind = kind;
  r.ssaa = ssaa;
  r.background = glm::vec4(0, 0, 0, 0);
  return r;
}

inline RasterRequest request_of(Target target, IdKind kind = IdKind::Primitive) {
  return request_of(static_cast<TargetMask>(target), kind);
}

inline std::set<int32_t> id_set(const cv::Mat& ids) {
  std::set<int32_t> s;
  for (auto it = ids.begin<int32_t>(); it != ids.end<int32_t>(); ++it)
    s.insert(*it);
  return s;
}

inline float srgb_to_linear(uint8_t c) {
  const float v = c / 255.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

inline Scene sphere_scene(int seg_u = 256, int seg_v = 128) {
  Mesh m;
  m.name = "sphere";
  add_sphere(m, glm::vec3(0.5f, -0.25f, 1.0f), 1.0f, seg_u, seg_v);
  set_ids(m, 5, 2);
  return scene_of({m});
}

inline Scene spheres_scene() {
  Mesh m;
  for (int i = 0; i < 4; ++i)
    add_sphere(m, glm::vec3(i * 0.9f, (i % 2) * 0.5f, 0), 0.6f, 64, 32);
  const size_t per = m.triangle_count() / 4;
  set_ids(m, 0, 1);
  for (size_t t = 0; t < m.triangle_count(); ++t)
    m.primitive_ids[t] = 1 + t / per;
  return scene_of({m});
}

}  // namespace sylva::test
