#include "npr/surface_samples.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/scene/instances.h"
#include "core/scene/texture_alpha.h"

namespace sylva {

namespace {

constexpr int kMaxCuts = 16;                 // sub-triangles per side
constexpr float kSpacingShare = 1.0f / 400;  // of the plant's diagonal
// At most this many samples from an instanced scene's instances (40 bytes each).
constexpr size_t kMaxSamples = size_t(1) << 22;

struct Corners {
  glm::vec3 p[3];
  glm::vec2 uv[3];
  uint32_t cluster = 0;
  uint32_t primitive = 0;
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
    out.primitives.push_back(c.primitive);
  });
}

// Samples of scene.meshes[meshes...] in their stored space; foliage (when not null) gets
// whether each sample's triangle is foliage.
void sample_meshes(const Scene& scene, const std::vector<uint32_t>& meshes, float spacing,
                   SurfaceSamples& out, std::vector<char>* foliage) {
  for (uint32_t mi : meshes) {
    const Mesh& m = scene.meshes[mi];
    const Material* cutout = nullptr;
    if (m.material >= 0 && size_t(m.material) < scene.materials.size() &&
        is_cutout(scene, scene.materials[size_t(m.material)]) && m.uvs.size() == m.positions.size())
      cutout = &scene.materials[size_t(m.material)];
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const Role role = t < m.roles.size() ? m.roles[t] : Role::Other;
      if (role == Role::Ground) continue;
      Corners c;
      c.cluster = t < m.cluster_ids.size() ? m.cluster_ids[t] : 0;
      c.primitive = t < m.primitive_ids.size() ? m.primitive_ids[t] : 0;
      for (int i = 0; i < 3; ++i) {
        const uint32_t v = m.indices[3 * t + size_t(i)];
        c.p[i] = m.positions[v];
        c.uv[i] = cutout ? m.uvs[v] : glm::vec2(0.0f);
      }
      sample_triangle(scene, cutout, c, spacing, out);
      if (foliage) foliage->resize(out.size(), role == Role::Foliage ? 1 : 0);
    }
  }
}

// A uniform number in [0, 1) from (instance, sample): keeps the thinning deterministic.
double unit_hash(uint64_t instance, uint64_t sample) {
  uint64_t z = (instance << 32) ^ sample ^ 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return double(z >> 11) * 0x1.0p-53;
}

// Instance i's copy of its plant's samples: moved into world space (in double, as the meshes
// are flattened), each kept with probability keep (its area divided by keep), the clusters
// those of the id buffer (core/scene/instances.h).
void add_instance(const SurfaceSamples& plant, const std::vector<char>& foliage, uint64_t i,
                  const glm::mat4& transform, const InstanceIdBase& base, uint32_t branch_cluster,
                  double keep, SurfaceSamples& out) {
  const glm::dmat4 t(transform);
  const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(t)));
  const double det = std::abs(glm::determinant(glm::dmat3(t)));
  for (size_t k = 0; k < plant.size(); ++k) {
    if (keep < 1.0 && unit_hash(i, k) >= keep) continue;
    const glm::dvec3 n = nm * glm::dvec3(plant.normals[k]);
    const double len = glm::length(n);
    out.positions.push_back(glm::vec3(t * glm::dvec4(plant.positions[k], 1.0)));
    out.normals.push_back(len > 0.0 ? glm::vec3(n / len) : plant.normals[k]);
    out.areas.push_back(float(double(plant.areas[k]) * det * len / keep));
    const bool own = foliage[k] || branch_cluster == 0;
    out.clusters.push_back(own ? plant.clusters[k] + base.cluster : branch_cluster);
    out.primitives.push_back(plant.primitives[k]);
    out.instances.push_back(uint32_t(i + 1));
  }
}

// The largest linear scale (cube root of |det|) of plant p's instances.
double largest_scale(const Scene& scene, size_t p) {
  double scale = 0.0;
  for (const Instance& inst : scene.instances)
    if (inst.plant == p)
      scale = std::max(
          scale, std::cbrt(std::abs(glm::determinant(glm::dmat3(glm::dmat4(inst.transform))))));
  return scale;
}

// Every plant sampled once in its own space (at the spacing its largest instance needs), then
// placed by each instance; past kMaxSamples the instances' samples are thinned evenly.
SurfaceSamples sample_instances(const Scene& scene, float spacing) {
  std::vector<SurfaceSamples> plants(scene.plants.size());
  std::vector<std::vector<char>> foliage(scene.plants.size());
  double total = 0.0;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const double scale = largest_scale(scene, p);
    if (!(scale > 0.0)) continue;
    sample_meshes(scene, scene.plants[p].meshes, float(spacing / scale), plants[p], &foliage[p]);
  }
  for (const Instance& inst : scene.instances)
    total += double(plants[inst.plant].size());
  // A little under the budget, so the seeded draw stays within it.
  const double keep = total > double(kMaxSamples) ? 0.998 * double(kMaxSamples) / total : 1.0;
  const IdLayout ids = id_layout(scene);
  SurfaceSamples out;
  out.spacing = spacing;
  const size_t reserve = size_t(std::min(total, double(kMaxSamples)));
  out.positions.reserve(reserve), out.normals.reserve(reserve);
  out.areas.reserve(reserve), out.clusters.reserve(reserve), out.instances.reserve(reserve);
  out.primitives.reserve(reserve);
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    add_instance(plants[inst.plant], foliage[inst.plant], i, inst.transform, ids.bases[i],
                 ids.branch_cluster, keep, out);
  }
  return out;
}

}  // namespace

SurfaceSamples sample_surfaces(const Scene& scene, float spacing) {
  SYLVA_CHECK(std::isfinite(spacing) && spacing > 0.0f, "sample_surfaces: spacing > 0");
  if (scene.instanced()) return sample_instances(scene, spacing);
  SurfaceSamples out;
  out.spacing = spacing;
  std::vector<uint32_t> all(scene.meshes.size());
  for (size_t m = 0; m < all.size(); ++m)
    all[m] = uint32_t(m);
  sample_meshes(scene, all, spacing, out, nullptr);
  return out;
}

float coverage_spacing(const Scene& scene) {
  return scene.bounds_except(Role::Ground).diagonal() * kSpacingShare;
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

SamplesHandle add_surface_samples_pass(RenderGraph& graph, const Scene* scene,
                                       std::shared_ptr<SurfaceSampleMemo> memo) {
  SYLVA_CHECK(scene != nullptr, "surface samples need a scene");
  const auto out = graph.resource<std::shared_ptr<const SurfaceSamples>>("surface-samples");
  graph.add_pass("surface-samples", {}, {out}, [out, scene, memo](PassContext& ctx) {
    ctx.write(out, coverage_samples(*scene, memo.get()));
  });
  return out;
}

}  // namespace sylva
