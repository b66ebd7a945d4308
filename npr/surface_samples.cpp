#include "npr/surface_samples.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/scene/texture_alpha.h"

namespace sylva {

namespace {

constexpr int kMaxCuts = 16;                 // sub-triangles per side
constexpr float kSpacingShare = 1.0f / 400;  // of the plant's diagonal

struct Corners {
  glm::vec3 p[3];
  glm::vec2 uv[3];
  uint32_t cluster = 0;
};

// The k x k sub-triangles' centroids in barycentric (u, v) of corners 1 and 2: for each
// upward sub-triangle (i, j) at ((i + 1/3) / k, (j + 1/3) / k), and each downward one at
// ((i + 2/3) / k, (j + 2/3) / k).
template <class Emit>
void for_each_centroid(int k, Emit emit) {
  const float inv = 1.0f / float(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      emit((float(i) + 1.0f / 3.0f) * inv, (float(j) + 1.0f / 3.0f) * inv);
      if (i + j < k - 1) emit((float(i) + 2.0f / 3.0f) * inv, (float(j) + 2.0f / 3.0f) * inv);
    }
}

void sample_triangle(const Scene& scene, const Material* cutout, const Corners& c, float spacing,
                     SurfaceSamples& out) {
  const glm::vec3 cross = glm::cross(c.p[1] - c.p[0], c.p[2] - c.p[0]);
  const float area = 0.5f * glm::length(cross);
  if (!(area > 0.0f)) return;
  const int k = std::clamp(int(std::ceil(std::sqrt(area) / spacing)), 1, kMaxCuts);
  const float piece = area / float(k * k);
  const glm::vec3 normal = cross / (2.0f * area);
  for_each_centroid(k, [&](float u, float v) {
    const float w = 1.0f - u - v;
    if (cutout && !drawn_at(scene, *cutout, w * c.uv[0] + u * c.uv[1] + v * c.uv[2])) return;
    out.positions.push_back(w * c.p[0] + u * c.p[1] + v * c.p[2]);
    out.normals.push_back(normal);
    out.areas.push_back(piece);
    out.clusters.push_back(c.cluster);
  });
}

}  // namespace

SurfaceSamples sample_surfaces(const Scene& scene, float spacing) {
  SYLVA_CHECK(std::isfinite(spacing) && spacing > 0.0f, "sample_surfaces: spacing > 0");
  SurfaceSamples out;
  out.spacing = spacing;
  for (const Mesh& m : scene.meshes) {
    const Material* cutout = nullptr;
    if (m.material >= 0 && size_t(m.material) < scene.materials.size() &&
        is_cutout(scene, scene.materials[size_t(m.material)]) && m.uvs.size() == m.positions.size())
      cutout = &scene.materials[size_t(m.material)];
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (t < m.roles.size() && m.roles[t] == Role::Ground) continue;
      Corners c;
      c.cluster = t < m.cluster_ids.size() ? m.cluster_ids[t] : 0;
      for (int i = 0; i < 3; ++i) {
        const uint32_t v = m.indices[3 * t + size_t(i)];
        c.p[i] = m.positions[v];
        c.uv[i] = cutout ? m.uvs[v] : glm::vec2(0.0f);
      }
      sample_triangle(scene, cutout, c, spacing, out);
    }
  }
  return out;
}

float coverage_spacing(const Scene& scene) {
  Bounds b;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (t < m.roles.size() && m.roles[t] == Role::Ground) continue;
      for (int i = 0; i < 3; ++i)
        b.extend(m.positions[m.indices[3 * t + size_t(i)]]);
    }
  return b.diagonal() * kSpacingShare;
}

std::shared_ptr<const SurfaceSamples> coverage_samples(const Scene& scene,
                                                       SurfaceSampleMemo* memo) {
  std::unique_lock<std::mutex> lock;
  if (memo) lock = std::unique_lock<std::mutex>(memo->mutex);
  std::shared_ptr<const SurfaceSamples> samples = memo ? memo->samples : nullptr;
  if (!samples) {
    const float spacing = coverage_spacing(scene);
    samples = std::make_shared<const SurfaceSamples>(
        spacing > 0.0f ? sample_surfaces(scene, spacing) : SurfaceSamples{});
    if (memo) memo->samples = samples;
  }
  return samples;
}

int add_surface_samples_pass(RenderGraph& graph, const Scene* scene,
                             std::shared_ptr<SurfaceSampleMemo> memo) {
  SYLVA_CHECK(scene != nullptr, "surface samples need a scene");
  const int out = graph.resource("surface-samples");
  graph.add_pass("surface-samples", {}, {out}, [out, scene, memo](PassContext& ctx) {
    ctx.write(out, coverage_samples(*scene, memo.get()));
  });
  return out;
}

}  // namespace sylva
