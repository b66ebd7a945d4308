#include "npr/generators.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "core/error.h"

namespace sylva {
namespace {

// Uniform integer in [0, n) from the raw 64-bit engine (rejection sampling), so the choice
// is the same on every standard library (std::uniform_int_distribution is not specified).
uint64_t bounded(std::mt19937_64& rng, uint64_t n) {
  const uint64_t limit = ~uint64_t(0) - (~uint64_t(0) % n);
  uint64_t r;
  do
    r = rng();
  while (r >= limit);
  return r % n;
}

// Keeps round(fraction * n) (at least 1) of the points, chosen by a seeded partial
// Fisher-Yates shuffle, in their original order.
std::vector<glm::vec3> keep_fraction(std::vector<glm::vec3> points, double fraction,
                                     uint64_t seed) {
  const size_t n = points.size();
  if (n == 0) return points;
  const size_t keep = std::clamp<size_t>(size_t(std::llround(fraction * double(n))), 1, n);
  if (keep == n) return points;
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i)
    order[i] = uint32_t(i);
  std::mt19937_64 rng(seed);
  for (size_t i = 0; i < keep; ++i)
    std::swap(order[i], order[i + bounded(rng, n - i)]);
  order.resize(keep);
  std::sort(order.begin(), order.end());
  std::vector<glm::vec3> out(keep);
  for (size_t i = 0; i < keep; ++i)
    out[i] = points[order[i]];
  return out;
}

void check_mesh(const Mesh& m) {
  SYLVA_CHECK(m.roles.size() == m.triangle_count(),
              "make_generators needs per-triangle roles (finish_scene)");
  SYLVA_CHECK(m.primitive_ids.size() == m.triangle_count(),
              "make_generators needs per-triangle primitive ids (finish_scene)");
}

}  // namespace

std::vector<glm::vec3> make_generators(const Scene& scene, const GeneratorOptions& options) {
  if (!std::isfinite(options.fraction) || !(options.fraction > 0.0) || options.fraction > 1.0)
    throw InputError("fraction", "must be in (0, 1], got " + std::to_string(options.fraction));
  for (const Mesh& m : scene.meshes)
    check_mesh(m);

  std::vector<glm::vec3> points;
  if (options.per_triangle) {
    // One generator per foliage triangle at its centroid, in triangle order.
    for (const Mesh& m : scene.meshes)
      for (size_t t = 0; t < m.triangle_count(); ++t) {
        if (m.roles[t] != Role::Foliage) continue;
        const glm::dvec3 a = m.positions[m.indices[3 * t]];
        const glm::dvec3 b = m.positions[m.indices[3 * t + 1]];
        const glm::dvec3 c = m.positions[m.indices[3 * t + 2]];
        points.push_back(glm::vec3((a + b + c) / 3.0));
      }
    return keep_fraction(std::move(points), options.fraction, options.seed);
  }

  // Luft et al. §3.1: a generator at the centre of mass of each foliage primitive, i.e. the
  // area-weighted mean of its triangle centroids; the mean of its corners when it has no area.
  // Ids are dense (at most one per triangle) after finish_scene; sparse ids are compacted.
  std::vector<uint32_t> ids;
  uint32_t max_id = 0;
  size_t foliage_triangles = 0;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (m.roles[t] == Role::Foliage) {
        max_id = std::max(max_id, m.primitive_ids[t]);
        ++foliage_triangles;
      }
  if (foliage_triangles == 0) return points;
  const bool dense = size_t(max_id) <= 2 * scene.triangle_count() + 16;
  if (!dense) {
    ids.reserve(foliage_triangles);
    for (const Mesh& m : scene.meshes)
      for (size_t t = 0; t < m.triangle_count(); ++t)
        if (m.roles[t] == Role::Foliage) ids.push_back(m.primitive_ids[t]);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
  auto slot_of = [&](uint32_t id) -> size_t {
    if (dense) return id;
    return size_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  };
  const size_t slots = dense ? size_t(max_id) + 1 : ids.size();

  struct Accum {
    glm::dvec3 weighted{0.0};  // sum of area * centroid, or of corners when `corners`
    double area = 0.0;
  };
  std::vector<Accum> acc(slots);
  std::vector<uint8_t> used(slots, 0);
  // Consecutive triangles of one primitive (the usual layout) are summed locally first.
  auto accumulate = [&](bool corners_only) {
    for (const Mesh& m : scene.meshes) {
      size_t run_slot = 0;
      Accum run;
      bool open = false;
      for (size_t t = 0; t < m.triangle_count(); ++t) {
        if (m.roles[t] != Role::Foliage) continue;
        const size_t slot = slot_of(m.primitive_ids[t]);
        if (corners_only && acc[slot].area != 0.0) continue;
        if (open && slot != run_slot) {
          acc[run_slot].weighted += run.weighted;
          acc[run_slot].area += run.area;
          run = Accum{};
        }
        run_slot = slot;
        open = true;
        used[slot] = 1;
        const glm::dvec3 a = m.positions[m.indices[3 * t]];
        const glm::dvec3 b = m.positions[m.indices[3 * t + 1]];
        const glm::dvec3 c = m.positions[m.indices[3 * t + 2]];
        if (corners_only) {
          run.weighted += a + b + c;
        } else {
          const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
          run.weighted += area * (a + b + c) / 3.0;
          run.area += area;
        }
      }
      if (open) {
        acc[run_slot].weighted += run.weighted;
        acc[run_slot].area += run.area;
      }
    }
  };
  accumulate(false);
  size_t count = 0;
  bool zero_area = false;
  for (size_t i = 0; i < slots; ++i) {
    count += used[i];
    zero_area = zero_area || (used[i] && acc[i].area == 0.0);
  }
  // Primitives without area: the mean of their corners (3 per triangle) instead.
  std::vector<uint32_t> corner_count;
  if (zero_area) {
    corner_count.assign(slots, 0);
    for (const Mesh& m : scene.meshes)
      for (size_t t = 0; t < m.triangle_count(); ++t)
        if (m.roles[t] == Role::Foliage) corner_count[slot_of(m.primitive_ids[t])] += 3;
    accumulate(true);
  }
  points.reserve(count);
  for (size_t i = 0; i < slots; ++i) {
    if (!used[i]) continue;  // an id without foliage triangles
    const Accum& s = acc[i];
    points.push_back(s.area > 0.0 ? glm::vec3(s.weighted / s.area)
                                  : glm::vec3(s.weighted / double(corner_count[i])));
  }
  return keep_fraction(std::move(points), options.fraction, options.seed);
}

}  // namespace sylva
