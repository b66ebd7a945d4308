#include "npr/density_field.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "npr/density_splat.h"

namespace sylva {
namespace {

// Most cells per axis of the hash grid: with a rho far below the generator extent the cell
// grows beyond rho (a query then touches at most 2 cells per axis), so cell coordinates and
// their 64-bit key never overflow.
constexpr double kMaxCellsPerAxis = double(1 << 20);
constexpr uint32_t kEmptySlot = std::numeric_limits<uint32_t>::max();

// floor(x) clamped to [0, n - 1]; NaN goes to 0.
int64_t clamp_cell(double x, int64_t n) {
  const double f = std::floor(x);
  if (!(f > 0.0)) return 0;
  if (f >= double(n - 1)) return n - 1;
  return int64_t(f);
}

uint64_t mix(uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  return k;
}

std::string number(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", double(v));
  return buf;
}

// Four doubles: GCC lowers these to two SSE2 registers or one AVX2 register, with the same
// per-lane rounding either way.
typedef double v4d __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));

// (By reference: passing AVX vectors by value would depend on the target's ABI.)
void load4(const float* p, v4d& out) {
  v4f f;
  std::memcpy(&f, p, sizeof f);
  out = __builtin_convertvector(f, v4d);
}

double lane_sum(const v4d& v) {
  return (v[0] + v[1]) + (v[2] + v[3]);
}

// Luft et al. Eq. 2 summed over n points (SoA) around q: branch-free (max(1 - s, 0)) in four
// fixed lanes, point i in lane i % 4, so the result does not depend on the vector width.
__attribute__((target_clones("avx2", "default"))) double kernel_sum(const float* x, const float* y,
                                                                    const float* z, size_t n,
                                                                    double qx, double qy, double qz,
                                                                    double inv_r2) {
  v4d acc = {0.0, 0.0, 0.0, 0.0};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    v4d px, py, pz;
    load4(x + i, px);
    load4(y + i, py);
    load4(z + i, pz);
    const v4d dx = qx - px, dy = qy - py, dz = qz - pz;
    const v4d d = 1.0 - (dx * dx + dy * dy + dz * dz) * inv_r2;
    const v4d t = d > 0.0 ? d : 0.0;
    acc += t * t;
  }
  for (size_t k = 0; i + k < n; ++k) {
    const double dx = qx - double(x[i + k]), dy = qy - double(y[i + k]), dz = qz - double(z[i + k]);
    const double d = 1.0 - (dx * dx + dy * dy + dz * dz) * inv_r2;
    const double t = d > 0.0 ? d : 0.0;
    acc[k] += t * t;
  }
  return lane_sum(acc);
}

// kernel_sum and the sum of the analytic gradients -4 (1 - s) (q - p) / rho^2.
__attribute__((target_clones("avx2", "default"))) double kernel_sum_gradient(
    const float* x, const float* y, const float* z, size_t n, double qx, double qy, double qz,
    double inv_r2, double grad[3]) {
  v4d acc = {0.0, 0.0, 0.0, 0.0}, gx = acc, gy = acc, gz = acc;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    v4d px, py, pz;
    load4(x + i, px);
    load4(y + i, py);
    load4(z + i, pz);
    const v4d dx = qx - px, dy = qy - py, dz = qz - pz;
    const v4d d = 1.0 - (dx * dx + dy * dy + dz * dz) * inv_r2;
    const v4d t = d > 0.0 ? d : 0.0;
    const v4d g = -4.0 * t * inv_r2;
    acc += t * t;
    gx += g * dx;
    gy += g * dy;
    gz += g * dz;
  }
  for (size_t k = 0; i + k < n; ++k) {
    const double dx = qx - double(x[i + k]), dy = qy - double(y[i + k]), dz = qz - double(z[i + k]);
    const double d = 1.0 - (dx * dx + dy * dy + dz * dz) * inv_r2;
    const double t = d > 0.0 ? d : 0.0;
    const double g = -4.0 * t * inv_r2;
    acc[k] += t * t;
    gx[k] += g * dx;
    gy[k] += g * dy;
    gz[k] += g * dz;
  }
  grad[0] = lane_sum(gx);
  grad[1] = lane_sum(gy);
  grad[2] = lane_sum(gz);
  return lane_sum(acc);
}

}  // namespace

// Uniform grid of cell size >= rho over the generators: points stored sorted by cell
// (generator order within a cell); cells addressed densely when the grid is small, through
// an open-addressing table of the occupied cells otherwise.
struct DensityField::Index {
  glm::dvec3 origin{0.0};
  double cell = 1.0;
  int64_t n[3] = {1, 1, 1};
  bool dense = true;
  Bounds bounds;
  std::vector<float> px, py, pz;    // generator coordinates in cell order
  std::vector<uint32_t> start;      // dense: first point of each cell, cells + 1 entries
  std::vector<uint64_t> keys;       // sparse: occupied cell keys, ascending
  std::vector<uint32_t> key_start;  // sparse: first point of keys[i], keys + 1 entries
  std::vector<uint32_t> table;      // sparse: index into keys or kEmptySlot
  uint64_t mask = 0;

  uint64_t key(int64_t x, int64_t y, int64_t z) const {
    return uint64_t(x) + uint64_t(n[0]) * (uint64_t(y) + uint64_t(n[1]) * uint64_t(z));
  }
  int64_t coord(double p, int axis) const { return clamp_cell((p - origin[axis]) / cell, n[axis]); }

  // Points of the cells x0..x1 of row (y, z), as one or more [begin, end) ranges.
  template <class Fn>
  void for_row(int64_t x0, int64_t x1, int64_t y, int64_t z, Fn&& fn) const {
    if (dense) {
      const uint64_t k = key(x0, y, z);
      fn(start[k], start[k + uint64_t(x1 - x0) + 1]);
      return;
    }
    for (int64_t x = x0; x <= x1; ++x) {
      const uint64_t k = key(x, y, z);
      for (uint64_t s = mix(k) & mask;; s = (s + 1) & mask) {
        const uint32_t i = table[s];
        if (i == kEmptySlot) break;
        if (keys[i] == k) {
          fn(key_start[i], key_start[i + 1]);
          break;
        }
      }
    }
  }

  // Every point range of the cells within `radius` of q, in a fixed order (cells z, y, x).
  template <class Fn>
  void for_near(const glm::dvec3& q, double radius, Fn&& fn) const {
    if (px.empty()) return;
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double l = (q[a] - radius - origin[a]) / cell;
      const double h = (q[a] + radius - origin[a]) / cell;
      // Entirely outside the grid (or NaN): nothing within radius.
      if (!(h >= 0.0) || !(l < double(n[a]))) return;
      lo[a] = clamp_cell(l, n[a]);
      hi[a] = clamp_cell(h, n[a]);
    }
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for_row(lo[0], hi[0], y, z, fn);
  }
};

DensityField::DensityField(std::vector<glm::vec3> generators, float rho, float tau)
    : m_generators(std::move(generators)), m_rho(rho), m_tau(tau) {
  if (!std::isfinite(rho) || !(rho > 0.0f))
    throw InputError("rho", "must be finite and > 0 (scene units), got " + number(rho));
  if (!std::isfinite(tau) || !(tau >= 0.0f))
    throw InputError("tau", "must be finite and >= 0, got " + number(tau));
  SYLVA_CHECK(m_generators.size() < size_t(kEmptySlot), "too many generators");

  m_index = std::make_unique<Index>();
  Index& ix = *m_index;
  for (const glm::vec3& p : m_generators) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError("generators", "positions must be finite");
    ix.bounds.extend(p);
  }
  const size_t count = m_generators.size();
  if (count == 0) return;

  const glm::dvec3 extent = glm::dvec3(ix.bounds.max) - glm::dvec3(ix.bounds.min);
  ix.origin = glm::dvec3(ix.bounds.min);
  ix.cell = std::max(double(rho), std::max({extent.x, extent.y, extent.z}) / kMaxCellsPerAxis);
  for (int a = 0; a < 3; ++a)
    ix.n[a] = std::min(int64_t(std::floor(extent[a] / ix.cell)) + 1, int64_t(kMaxCellsPerAxis) + 1);
  const uint64_t cells = uint64_t(ix.n[0]) * uint64_t(ix.n[1]) * uint64_t(ix.n[2]);

  std::vector<uint64_t> key(count);
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3 p = m_generators[i];
    key[i] = ix.key(ix.coord(p.x, 0), ix.coord(p.y, 1), ix.coord(p.z, 2));
  }

  ix.px.resize(count);
  ix.py.resize(count);
  ix.pz.resize(count);
  auto put = [&ix](size_t slot, const glm::vec3& p) {
    ix.px[slot] = p.x;
    ix.py[slot] = p.y;
    ix.pz[slot] = p.z;
  };
  ix.dense = cells <= 4 * uint64_t(count) + (1u << 16);
  if (ix.dense) {
    // Counting sort by cell: stable, so generator order within a cell.
    ix.start.assign(size_t(cells) + 1, 0);
    for (uint64_t k : key)
      ++ix.start[size_t(k) + 1];
    for (size_t c = 0; c < size_t(cells); ++c)
      ix.start[c + 1] += ix.start[c];
    std::vector<uint32_t> fill(ix.start.begin(), ix.start.end() - 1);
    for (size_t i = 0; i < count; ++i)
      put(fill[size_t(key[i])]++, m_generators[i]);
    return;
  }

  std::vector<std::pair<uint64_t, uint32_t>> order(count);
  for (size_t i = 0; i < count; ++i)
    order[i] = {key[i], uint32_t(i)};
  std::sort(order.begin(), order.end());
  for (size_t i = 0; i < count; ++i) {
    put(i, m_generators[order[i].second]);
    if (i == 0 || order[i].first != order[i - 1].first) {
      ix.keys.push_back(order[i].first);
      ix.key_start.push_back(uint32_t(i));
    }
  }
  ix.key_start.push_back(uint32_t(count));
  size_t slots = 16;
  while (slots < 2 * ix.keys.size())
    slots *= 2;
  ix.mask = slots - 1;
  ix.table.assign(slots, kEmptySlot);
  for (size_t i = 0; i < ix.keys.size(); ++i) {
    uint64_t s = mix(ix.keys[i]) & ix.mask;
    while (ix.table[s] != kEmptySlot)
      s = (s + 1) & ix.mask;
    ix.table[s] = uint32_t(i);
  }
}

DensityField::~DensityField() = default;
DensityField::DensityField(DensityField&&) noexcept = default;
DensityField& DensityField::operator=(DensityField&&) noexcept = default;

Bounds DensityField::generator_bounds() const {
  return m_index ? m_index->bounds : Bounds{};
}

float DensityField::value(const glm::vec3& q) const {
  SYLVA_CHECK(m_index, "DensityField used after move");
  const Index& ix = *m_index;
  const glm::dvec3 qd(q);
  const double inv_r2 = 1.0 / (double(m_rho) * double(m_rho));
  double sum = 0.0;
  ix.for_near(qd, m_rho, [&](uint32_t b, uint32_t e) {
    sum += kernel_sum(ix.px.data() + b, ix.py.data() + b, ix.pz.data() + b, e - b, qd.x, qd.y, qd.z,
                      inv_r2);
  });
  return float(sum - double(m_tau));  // Luft et al. Eq. 3
}

float DensityField::value_and_gradient(const glm::vec3& q, glm::vec3& gradient) const {
  SYLVA_CHECK(m_index, "DensityField used after move");
  const Index& ix = *m_index;
  const glm::dvec3 qd(q);
  const double inv_r2 = 1.0 / (double(m_rho) * double(m_rho));
  double sum = 0.0;
  glm::dvec3 grad(0.0);
  ix.for_near(qd, m_rho, [&](uint32_t b, uint32_t e) {
    double g[3];
    sum += kernel_sum_gradient(ix.px.data() + b, ix.py.data() + b, ix.pz.data() + b, e - b, qd.x,
                               qd.y, qd.z, inv_r2, g);
    grad += glm::dvec3(g[0], g[1], g[2]);
  });
  gradient = glm::vec3(grad);
  return float(sum - double(m_tau));  // Luft et al. Eq. 3
}

void DensityField::fill_grid(ScalarGrid& grid) const {
  SYLVA_CHECK(m_index, "DensityField used after move");
  SYLVA_CHECK(grid.dims.x >= 1 && grid.dims.y >= 1 && grid.dims.z >= 1, "grid dims not set");
  SYLVA_CHECK(std::isfinite(grid.spacing) && grid.spacing > 0.0f, "grid spacing must be > 0");
  grid.values.resize(size_t(grid.dims.x) * size_t(grid.dims.y) * size_t(grid.dims.z));
  const auto nodes = density_splat::grid_nodes(grid, m_rho);
  const auto boxes = density_splat::node_boxes(m_generators, nodes, m_rho);
  const auto slabs = density_splat::slab_generators(boxes, nodes);
  density_splat::splat_slabs(m_generators, boxes, slabs, nodes, m_rho, m_tau, grid);
}

}  // namespace sylva
