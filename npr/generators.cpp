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

// Throws on a fraction outside (0, 1]; checks that every mesh has per-triangle attributes.
void check_inputs(const Scene& scene, const GeneratorOptions& options) {
  if (!std::isfinite(options.fraction) || !(options.fraction > 0.0) || options.fraction > 1.0)
    throw InputError("fraction", "must be in (0, 1], got " + std::to_string(options.fraction));
  for (const Mesh& m : scene.meshes) {
    SYLVA_CHECK(m.roles.size() == m.triangle_count(),
                "make_generators needs per-triangle roles (finish_scene)");
    SYLVA_CHECK(m.primitive_ids.size() == m.triangle_count(),
                "make_generators needs per-triangle primitive ids (finish_scene)");
  }
}

// The corners of triangle t of m, in double precision.
struct Corners {
  glm::dvec3 a, b, c;
};
Corners corners(const Mesh& m, size_t t) {
  return {m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
          m.positions[m.indices[3 * t + 2]]};
}

// One generator per foliage triangle at its centroid, in triangle order.
std::vector<glm::vec3> triangle_centroids(const Scene& scene) {
  std::vector<glm::vec3> points;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (m.roles[t] != Role::Foliage) continue;
      const auto [a, b, c] = corners(m, t);
      points.push_back(glm::vec3((a + b + c) / 3.0));
    }
  return points;
}

// Foliage primitive ids mapped to accumulator slots: ids are dense (at most one per triangle)
// after finish_scene and used as they are; sparse ids are compacted to their rank.
struct PrimitiveSlots {
  size_t foliage_triangles = 0;
  bool dense = true;
  std::vector<uint32_t> ids;  // sparse: the distinct foliage ids, ascending
  size_t count = 0;           // slots

  size_t of(uint32_t id) const {
    if (dense) return id;
    return size_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  }
};

// Counts the foliage triangles and chooses dense or compacted slots for their primitive ids.
PrimitiveSlots map_primitive_slots(const Scene& scene) {
  PrimitiveSlots slots;
  uint32_t max_id = 0;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (m.roles[t] == Role::Foliage) {
        max_id = std::max(max_id, m.primitive_ids[t]);
        ++slots.foliage_triangles;
      }
  if (slots.foliage_triangles == 0) return slots;
  slots.dense = size_t(max_id) <= 2 * scene.triangle_count() + 16;
  if (!slots.dense) {
    slots.ids.reserve(slots.foliage_triangles);
    for (const Mesh& m : scene.meshes)
      for (size_t t = 0; t < m.triangle_count(); ++t)
        if (m.roles[t] == Role::Foliage) slots.ids.push_back(m.primitive_ids[t]);
    std::sort(slots.ids.begin(), slots.ids.end());
    slots.ids.erase(std::unique(slots.ids.begin(), slots.ids.end()), slots.ids.end());
  }
  slots.count = slots.dense ? size_t(max_id) + 1 : slots.ids.size();
  return slots;
}

struct Accum {
  glm::dvec3 weighted{0.0};  // sum of area * centroid, or of corners when `corners`
  double area = 0.0;
};

// Per-slot sums over the foliage triangles of each primitive.
struct PrimitiveSums {
  std::vector<Accum> acc;
  std::vector<uint8_t> used;  // the slot has foliage triangles

  explicit PrimitiveSums(size_t slots) : acc(slots), used(slots, 0) {}
  void add(size_t slot, const Accum& run) {
    acc[slot].weighted += run.weighted;
    acc[slot].area += run.area;
  }
};

// Adds every foliage triangle to its primitive's slot: area and area-weighted centroid, or
// with corners_only the corners of the primitives that have no area yet. Consecutive
// triangles of one primitive (the usual layout) are summed locally first.
void accumulate(const Scene& scene, const PrimitiveSlots& slots, bool corners_only,
                PrimitiveSums& sums) {
  for (const Mesh& m : scene.meshes) {
    size_t run_slot = 0;
    Accum run;
    bool open = false;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (m.roles[t] != Role::Foliage) continue;
      const size_t slot = slots.of(m.primitive_ids[t]);
      if (corners_only && sums.acc[slot].area != 0.0) continue;
      if (open && slot != run_slot) {
        sums.add(run_slot, run);
        run = Accum{};
      }
      run_slot = slot;
      open = true;
      sums.used[slot] = 1;
      const auto [a, b, c] = corners(m, t);
      if (corners_only) {
        run.weighted += a + b + c;
      } else {
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        run.weighted += area * (a + b + c) / 3.0;
        run.area += area;
      }
    }
    if (open) sums.add(run_slot, run);
  }
}

// Whether a primitive with foliage triangles has no area (its corners then stand in).
bool any_zero_area(const PrimitiveSums& sums) {
  bool zero_area = false;
  for (size_t i = 0; i < sums.acc.size(); ++i)
    zero_area = zero_area || (sums.used[i] && sums.acc[i].area == 0.0);
  return zero_area;
}

// Corners per slot (3 per foliage triangle), the divisor of a primitive without area.
std::vector<uint32_t> corner_counts(const Scene& scene, const PrimitiveSlots& slots) {
  std::vector<uint32_t> corner_count(slots.count, 0);
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (m.roles[t] == Role::Foliage) corner_count[slots.of(m.primitive_ids[t])] += 3;
  return corner_count;
}

// The centre of mass of each used slot, in slot (primitive id) order.
std::vector<glm::vec3> centres_of_mass(const PrimitiveSums& sums,
                                       const std::vector<uint32_t>& corner_count) {
  size_t count = 0;
  for (uint8_t u : sums.used)
    count += u;
  std::vector<glm::vec3> points;
  points.reserve(count);
  for (size_t i = 0; i < sums.acc.size(); ++i) {
    if (!sums.used[i]) continue;  // an id without foliage triangles
    const Accum& s = sums.acc[i];
    points.push_back(s.area > 0.0 ? glm::vec3(s.weighted / s.area)
                                  : glm::vec3(s.weighted / double(corner_count[i])));
  }
  return points;
}

}  // namespace

std::vector<glm::vec3> make_generators(const Scene& scene, const GeneratorOptions& options) {
  check_inputs(scene, options);
  if (options.per_triangle)
    return keep_fraction(triangle_centroids(scene), options.fraction, options.seed);

  // Luft et al. §3.1: a generator at the centre of mass of each foliage primitive, i.e. the
  // area-weighted mean of its triangle centroids; the mean of its corners when it has no area.
  const PrimitiveSlots slots = map_primitive_slots(scene);
  if (slots.foliage_triangles == 0) return {};
  PrimitiveSums sums(slots.count);
  accumulate(scene, slots, false, sums);
  // Primitives without area: the mean of their corners (3 per triangle) instead.
  std::vector<uint32_t> corner_count;
  if (any_zero_area(sums)) {
    corner_count = corner_counts(scene, slots);
    accumulate(scene, slots, true, sums);
  }
  return keep_fraction(centres_of_mass(sums, corner_count), options.fraction, options.seed);
}

}  // namespace sylva
