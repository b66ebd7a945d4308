#include "npr/scalar_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace sylva {
namespace {

// Clamps x into [0, hi]; NaN goes to 0 so a bad query cannot index out of range.
float clamp_coord(float x, float hi) {
  return x > 0.0f ? (x < hi ? x : hi) : 0.0f;
}

// The cell (lower corner index) holding grid coordinate u in [0, n - 1] and the fraction
// within it; the last node belongs to the last cell (fraction 1).
void locate(float u, int n, int& i, float& f) {
  i = std::min(int(u), n - 2);
  f = u - float(i);
}

struct Cell {
  int x, y, z;
  float fx, fy, fz;
};

Cell locate_point(const ScalarGrid& g, const glm::vec3& p) {
  SYLVA_CHECK(!g.empty() && g.dims.x >= 2 && g.dims.y >= 2 && g.dims.z >= 2,
              "sampling an empty scalar grid");
  SYLVA_CHECK(g.values.size() == size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z),
              "scalar grid values do not match its dims");
  const glm::vec3 u = (p - g.origin) / g.spacing;
  Cell c{};
  locate(clamp_coord(u.x, float(g.dims.x - 1)), g.dims.x, c.x, c.fx);
  locate(clamp_coord(u.y, float(g.dims.y - 1)), g.dims.y, c.y, c.fy);
  locate(clamp_coord(u.z, float(g.dims.z - 1)), g.dims.z, c.z, c.fz);
  return c;
}

}  // namespace

float ScalarGrid::sample(const glm::vec3& p) const {
  const Cell c = locate_point(*this, p);
  float v[2][2];  // [z][y], interpolated along x
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy) {
      const float a = at(c.x, c.y + dy, c.z + dz);
      const float b = at(c.x + 1, c.y + dy, c.z + dz);
      v[dz][dy] = a + (b - a) * c.fx;
    }
  const float v0 = v[0][0] + (v[0][1] - v[0][0]) * c.fy;
  const float v1 = v[1][0] + (v[1][1] - v[1][0]) * c.fy;
  return v0 + (v1 - v0) * c.fz;
}

glm::vec3 ScalarGrid::sample_gradient(const glm::vec3& p) const {
  // Derivatives of the trilinear interpolant of the cell holding the (clamped) point.
  const Cell c = locate_point(*this, p);
  float n[2][2][2];  // [z][y][x]
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
        n[dz][dy][dx] = at(c.x + dx, c.y + dy, c.z + dz);
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  // d/dx: x-differences interpolated in y and z.
  const float gx = lerp(lerp(n[0][0][1] - n[0][0][0], n[0][1][1] - n[0][1][0], c.fy),
                        lerp(n[1][0][1] - n[1][0][0], n[1][1][1] - n[1][1][0], c.fy), c.fz);
  const float gy = lerp(lerp(n[0][1][0] - n[0][0][0], n[0][1][1] - n[0][0][1], c.fx),
                        lerp(n[1][1][0] - n[1][0][0], n[1][1][1] - n[1][0][1], c.fx), c.fz);
  const float gz = lerp(lerp(n[1][0][0] - n[0][0][0], n[1][0][1] - n[0][0][1], c.fx),
                        lerp(n[1][1][0] - n[0][1][0], n[1][1][1] - n[0][1][1], c.fx), c.fy);
  return glm::vec3(gx, gy, gz) / spacing;
}

ScalarGrid make_grid(const glm::vec3& lo, const glm::vec3& hi, int cells) {
  if (cells < 2 || cells > 1024)
    throw InputError(
        "grid", "cells along the longest axis must be in [2, 1024], got " + std::to_string(cells));
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(lo[a] <= hi[a]))
      throw InputError("grid", "the box must be finite with lo <= hi on every axis");
  const glm::dvec3 extent = glm::dvec3(hi) - glm::dvec3(lo);
  const double longest = std::max({extent.x, extent.y, extent.z});
  // A point box has no scale of its own; any positive spacing covers it.
  const double spacing = longest > 0.0 ? longest / cells : 1.0;

  ScalarGrid g;
  g.spacing = float(spacing);
  if (!(g.spacing > 0.0f) || !std::isfinite(g.spacing))
    throw InputError("grid", "the box is too small or too large for float spacing");
  for (int a = 0; a < 3; ++a) {
    // The longest axis gets exactly `cells`; the others as many as cover their extent
    // (never more than `cells`, which also absorbs rounding), centred on the box.
    const int n =
        extent[a] == longest ? cells : std::clamp(int(std::ceil(extent[a] / spacing)), 2, cells);
    g.dims[a] = n + 1;
    const double centre = 0.5 * (double(lo[a]) + double(hi[a]));
    g.origin[a] = extent[a] == longest && longest > 0.0 ? lo[a] : float(centre - 0.5 * n * spacing);
  }
  g.values.assign(size_t(g.dims.x) * size_t(g.dims.y) * size_t(g.dims.z), 0.0f);
  return g;
}

}  // namespace sylva
