// A regular grid of scalar samples over an axis-aligned box: the density field sampled at
// grid nodes (Luft et al. §3.1), read by marching cubes and by trilinear lookups.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace sylva {

struct ScalarGrid {
  glm::ivec3 dims{0};         // samples per axis, each >= 2 when not empty
  glm::vec3 origin{0.0f};     // world position of sample (0, 0, 0), scene units
  float spacing = 1.0f;       // distance between neighbouring samples, scene units, > 0
  std::vector<float> values;  // x fastest: index(x, y, z) = x + dims.x * (y + dims.y * z)

  bool empty() const { return values.empty(); }
  size_t index(int x, int y, int z) const {
    return size_t(x) + size_t(dims.x) * (size_t(y) + size_t(dims.y) * size_t(z));
  }
  float at(int x, int y, int z) const { return values[index(x, y, z)]; }
  glm::vec3 position(int x, int y, int z) const {
    return origin + spacing * glm::vec3(float(x), float(y), float(z));
  }
  // Trilinear interpolation; points outside the box are clamped onto it.
  float sample(const glm::vec3& p) const;
  // Gradient of the trilinear interpolant (scene units^-1); clamped like sample().
  glm::vec3 sample_gradient(const glm::vec3& p) const;
};

// A grid covering `lo`..`hi` (lo < hi per axis or a point) with `cells` cells along the
// longest axis (cells in [2, 1024]); the other axes get as many cells of the same spacing
// as needed to cover the box (at least 2). Values are zero-filled.
ScalarGrid make_grid(const glm::vec3& lo, const glm::vec3& hi, int cells);

}  // namespace sylva
