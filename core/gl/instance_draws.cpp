#include "core/gl/instance_draws.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "core/error.h"
#include "core/gl/shaders.h"
#include "core/scene/lod.h"

namespace sylva {

namespace {

// The plant's bounding sphere in plant space: the box's centre, through its farthest vertex;
// without_ground: of its triangles that are not ground only (radius < 0: none).
glm::vec4 plant_sphere(const Scene& scene, size_t plant, bool without_ground = false) {
  std::vector<glm::vec3> points;
  for (uint32_t mi : plant_meshes(scene, plant)) {
    const Mesh& m = scene.meshes[mi];
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (!without_ground || t >= m.roles.size() || m.roles[t] != Role::Ground)
        for (int k = 0; k < 3; ++k)
          points.push_back(m.positions[m.indices[3 * t + size_t(k)]]);
  }
  Bounds b;
  for (const glm::vec3& p : points)
    b.extend(p);
  if (b.empty()) return glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
  const glm::vec3 c = b.center();
  float r = 0.0f;
  for (const glm::vec3& p : points)
    r = std::max(r, glm::length(p - c));
  return glm::vec4(c, r * 1.001f + 1e-6f);
}

// Instance `t`'s world bounding sphere of a plant sphere `s`.
glm::vec4 world_sphere(const glm::vec4& s, const glm::mat4& t) {
  float scale = 0.0f;
  for (int k = 0; k < 3; ++k)
    scale = std::max(scale, glm::length(glm::vec3(t[k])));
  return glm::vec4(glm::vec3(t * glm::vec4(glm::vec3(s), 1.0f)), s.w * scale);
}

bool in_view(const std::array<glm::vec4, 6>& planes, const glm::vec4& s) {
  for (const glm::vec4& p : planes)
    if (glm::dot(glm::vec3(p), glm::vec3(s)) + p.w < -s.w) return false;
  return true;
}

// The view volume's six planes (Gribb & Hartmann), normalised, inside where >= 0.
std::array<glm::vec4, 6> view_planes(const Camera& camera) {
  const glm::mat4 m = glm::transpose(camera.proj * camera.view);  // rows as columns
  std::array<glm::vec4, 6> planes = {m[3] + m[0], m[3] - m[0], m[3] + m[1],
                                     m[3] - m[1], m[3] + m[2], m[3] - m[2]};
  for (glm::vec4& p : planes) {
    const float len = glm::length(glm::vec3(p));
    if (len > 0.0f) p /= len;
  }
  return planes;
}

}  // namespace

Sphere visible_instances_sphere(const Scene& scene, const Camera& camera) {
  Sphere out;
  if (!scene.instanced()) return out;
  std::vector<glm::vec4> spheres;
  for (size_t p = 0; p < scene.plants.size(); ++p)
    spheres.push_back(plant_sphere(scene, p, true));
  const std::array<glm::vec4, 6> planes = view_planes(camera);
  std::vector<glm::vec4> seen;
  Bounds b;
  for (const Instance& inst : scene.instances) {
    if (spheres[inst.plant].w < 0.0f) continue;
    const glm::vec4 s = world_sphere(spheres[inst.plant], inst.transform);
    if (!in_view(planes, s)) continue;
    seen.push_back(s);
    b.extend(glm::vec3(s) - glm::vec3(s.w));
    b.extend(glm::vec3(s) + glm::vec3(s.w));
  }
  if (seen.empty()) return out;
  out.centre = b.center();
  out.radius = 0.0f;
  for (const glm::vec4& s : seen)
    out.radius = std::max(out.radius, glm::length(glm::vec3(s) - out.centre) + s.w);
  return out;
}

void InstanceDraws::upload(const Scene& scene) {
  release();
  m_records.clear();
  m_plant.clear();
  m_mirrored.clear();
  m_spheres.clear();
  m_triangles.clear();
  m_levels.clear();
  if (!scene.instanced()) return;
  const IdLayout ids = id_layout(scene);
  m_branch_cluster = ids.branch_cluster;
  for (size_t p = 0; p < scene.plants.size(); ++p)
    m_spheres.push_back(plant_sphere(scene, p));
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    Record r{};
    for (int c = 0; c < 4; ++c)
      r.model[c] = inst.transform[c];
    const glm::mat3 n = normal_matrix(inst.transform);
    for (int c = 0; c < 3; ++c)
      r.normal[c] = glm::vec4(n[c], 0.0f);
    r.ids =
        glm::uvec4(ids.bases[i].primitive, ids.bases[i].cluster, ids.bases[i].object, inst.plant);
    m_records.push_back(r);
    m_plant.push_back(inst.plant);
    m_mirrored.push_back(glm::determinant(glm::mat3(inst.transform)) < 0.0f);
  }
}

void InstanceDraws::release() {
  if (m_buffer) glDeleteBuffers(1, &m_buffer);
  m_buffer = 0;
  m_capacity = 0;
}

void InstanceDraws::set_levels(const std::vector<size_t>& plant_triangles,
                               const std::vector<int>& levels) {
  SYLVA_CHECK(plant_triangles.size() == m_spheres.size() && levels.size() == m_spheres.size(),
              "InstanceDraws::set_levels: one entry per plant");
  m_triangles = plant_triangles;
  m_levels = levels;
}

int InstanceDraws::level_of(size_t i, const glm::vec3& centre, float radius, const Camera& camera,
                            int ssaa) const {
  if (m_triangles.empty() || m_levels[m_plant[i]] == 0) return 0;
  // The projected radius in pixels: proj[1][1] maps a view-space height to half the image
  // height, divided by the depth under perspective (kept at least the radius, so an instance
  // around the eye stays whole).
  const double half_height = 0.5 * double(camera.height) * double(ssaa);
  double r_px = double(radius) * double(camera.proj[1][1]) * half_height;
  if (!camera.ortho) {
    const double depth = -double((camera.view * glm::vec4(centre, 1.0f)).z);
    r_px /= std::max(depth, double(radius));
  }
  const double pixels = 3.14159265358979 * r_px * r_px;
  double triangles = double(m_triangles[m_plant[i]]);
  int level = 0;
  while (level < m_levels[m_plant[i]] && triangles > pixels * kLodTrianglesPerPixel) {
    triangles *= 0.5;
    ++level;
  }
  return level;
}

std::vector<InstanceBatch> InstanceDraws::prepare(const Camera& camera, int ssaa, size_t* drawn) {
  const std::array<glm::vec4, 6> planes = view_planes(camera);
  // Per instance: -1 when out of view, else its level.
  std::vector<int> level(m_records.size(), -1);
  for (size_t i = 0; i < m_records.size(); ++i) {
    const glm::vec4 s = m_spheres[m_plant[i]];
    if (s.w < 0.0f) continue;
    const glm::mat4 model(m_records[i].model[0], m_records[i].model[1], m_records[i].model[2],
                          m_records[i].model[3]);
    const glm::vec4 w = world_sphere(s, model);
    if (in_view(planes, w)) level[i] = level_of(i, glm::vec3(w), w.w, camera, ssaa);
  }
  std::vector<Record> data;
  std::vector<InstanceBatch> batches;
  for (uint32_t plant = 0; plant < m_spheres.size(); ++plant)
    for (int l = 0; l <= kLodLevels; ++l)
      for (bool mirrored : {false, true}) {
        InstanceBatch b;
        b.plant = plant;
        b.level = l;
        b.mirrored = mirrored;
        b.offset = GLintptr(data.size() * sizeof(Record));
        for (size_t i = 0; i < m_records.size(); ++i)
          if (m_plant[i] == plant && m_mirrored[i] == mirrored && level[i] == l)
            data.push_back(m_records[i]);
        b.count = GLsizei(data.size() - size_t(b.offset) / sizeof(Record));
        if (b.count > 0) batches.push_back(b);
      }
  if (drawn) *drawn = data.size();
  if (!m_buffer) glGenBuffers(1, &m_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, m_buffer);
  if (data.size() > m_capacity) {
    m_capacity = data.size();
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m_capacity * sizeof(Record)), nullptr, GL_STREAM_DRAW);
  }
  if (!data.empty())
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(data.size() * sizeof(Record)), data.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return batches;
}

void InstanceDraws::bind(const InstanceBatch& batch) const {
  glBindBuffer(GL_ARRAY_BUFFER, m_buffer);
  const auto stride = GLsizei(sizeof(Record));
  auto at = [&](size_t offset) {
    return reinterpret_cast<const void*>(size_t(batch.offset) + offset);
  };
  for (GLuint c = 0; c < 4; ++c) {
    glVertexAttribPointer(kAttribModel + c, 4, GL_FLOAT, GL_FALSE, stride,
                          at(offsetof(Record, model) + 16 * c));
    glVertexAttribDivisor(kAttribModel + c, 1);
    glEnableVertexAttribArray(kAttribModel + c);
  }
  for (GLuint c = 0; c < 3; ++c) {
    glVertexAttribPointer(kAttribNormalMatrix + c, 3, GL_FLOAT, GL_FALSE, stride,
                          at(offsetof(Record, normal) + 16 * c));
    glVertexAttribDivisor(kAttribNormalMatrix + c, 1);
    glEnableVertexAttribArray(kAttribNormalMatrix + c);
  }
  glVertexAttribIPointer(kAttribIdBase, 4, GL_UNSIGNED_INT, stride, at(offsetof(Record, ids)));
  glVertexAttribDivisor(kAttribIdBase, 1);
  glEnableVertexAttribArray(kAttribIdBase);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace sylva
