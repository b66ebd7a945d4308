#include "npr/density_splat.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sylva::density_splat {
namespace {

// [ceil(lo), floor(hi)] clamped to [first, last]; empty (a > e) when they do not meet.
void node_span(double lo, double hi, int first, int last, int& a, int& e) {
  lo = std::max(double(first), lo);
  hi = std::min(double(last), hi);
  if (!(lo <= hi)) {
    a = 1;
    e = 0;
    return;
  }
  // Both ends are >= 0 here, where truncation is floor (and SSE2 has no fast ceil).
  a = int(lo);
  a += double(a) < lo ? 1 : 0;
  e = int(hi);
}

// Adds one generator's kernel (Luft et al. Eq. 2) to `planes` consecutive planes starting at
// `dst`: s = u[x] + v[y] + w[z] (squared distances over rho^2 per axis), D = (1 - s)^2 where
// s < 1. (gx, gy) is the generator in node units, `widen` the slack for node drift. Each plane
// visits the square around the ball's cross-section without branches (max(1 - s, 0) zeroes the
// corners): cheaper than exact row spans, whose set-up and mispredictions cost more than the nodes
// they save. Compiled for AVX2 too (no FMA, so every version gives the same bytes).
__attribute__((target_clones("avx2", "default"))) void splat_planes(
    double* dst, size_t plane, int nx, int planes, int yl, int yh, int xl, int xh, const double* u,
    const double* v, const double* w, double gx, double gy, double rho_nodes, double widen) {
  for (int z = 0; z < planes; ++z) {
    const double cz = 1.0 - w[z];
    if (!(cz > 0.0)) continue;
    // The cross-section's radius in node units (a node rounding moves across the rim adds
    // (1 - s)^2 ~ 0).
    const double half = rho_nodes * std::sqrt(cz) + widen;
    int xa, xe, ya, ye;
    node_span(gx - half, gx + half, xl, xh, xa, xe);
    node_span(gy - half, gy + half, yl, yh, ya, ye);
    double* dst_plane = dst + size_t(z) * plane;
    for (int y = ya; y <= ye; ++y) {
      const double c = cz - v[y];
      double* row = dst_plane + size_t(y) * size_t(nx);
#pragma omp simd
      for (int x = xa; x <= xe; ++x) {
        const double d = c - u[x];
        const double t = 0.5 * (d + std::abs(d));  // max(d, 0), branch-free
        row[x] += t * t;
      }
    }
  }
}

// Whether the box holds any node.
bool touches(const NodeBox& b) {
  return b.lo[0] <= b.hi[0] && b.lo[1] <= b.hi[1] && b.lo[2] <= b.hi[2];
}

// One thread's working memory: a slab's sums, and squared distances over rho^2 per axis.
struct SlabScratch {
  std::vector<double> acc, u, v, w;
  SlabScratch(const GridNodes& nodes, int slab)
      : acc(nodes.plane * size_t(slab)),
        u(static_cast<size_t>(nodes.dims[0])),
        v(static_cast<size_t>(nodes.dims[1])),
        w(static_cast<size_t>(nodes.dims[2])) {}
};

// Adds generator p (its box b) to the slab's planes z_begin..z_end - 1.
void splat_generator(const glm::dvec3& p, const NodeBox& b, int z_begin, int z_end,
                     const GridNodes& nodes, double inv_r2, double rho_nodes, SlabScratch& s) {
  const std::vector<double>&xs = nodes.coords[0], &ys = nodes.coords[1], &zs = nodes.coords[2];
  const double h = nodes.h;
  const int xl = b.lo[0], xh = b.hi[0], yl = b.lo[1], yh = b.hi[1];
  const int zl = std::max(b.lo[2], z_begin), zh = std::min(b.hi[2], z_end - 1);
  // Squared distances over rho^2 per axis: s = u[x] + v[y] + w[z], and
  // D = (1 - s)^2 where s < 1 (Luft et al. Eq. 2).
  for (int x = xl; x <= xh; ++x) {
    const double d = xs[size_t(x)] - p.x;
    s.u[size_t(x)] = d * d * inv_r2;
  }
  for (int y = yl; y <= yh; ++y) {
    const double d = ys[size_t(y)] - p.y;
    s.v[size_t(y)] = d * d * inv_r2;
  }
  for (int z = zl; z <= zh; ++z) {
    const double d = zs[size_t(z)] - p.z;
    s.w[size_t(z)] = d * d * inv_r2;
  }
  const double gx = (p.x - xs[0]) / h;  // generator x in node units
  splat_planes(s.acc.data() + size_t(zl - z_begin) * nodes.plane, nodes.plane, nodes.dims[0],
               zh - zl + 1, yl, yh, xl, xh, s.u.data(), s.v.data(), s.w.data() + zl, gx,
               (p.y - ys[0]) / h, rho_nodes, nodes.widen);
}

// Luft et al. Eq. 3: F = sum D_i - tau, from the slab's sums into its planes of the grid.
void write_slab(const std::vector<double>& acc, int z_begin, int z_end, size_t plane, double tau,
                ScalarGrid& grid) {
  for (int z = z_begin; z < z_end; ++z) {
    const double* src = acc.data() + size_t(z - z_begin) * plane;
    float* dst = grid.values.data() + size_t(z) * plane;
    for (size_t i = 0; i < plane; ++i)
      dst[i] = float(src[i] - tau);
  }
}

}  // namespace

GridNodes grid_nodes(const ScalarGrid& grid, double rho) {
  GridNodes nodes;
  nodes.dims[0] = grid.dims.x;
  nodes.dims[1] = grid.dims.y;
  nodes.dims[2] = grid.dims.z;
  nodes.plane = size_t(grid.dims.x) * size_t(grid.dims.y);
  nodes.h = grid.spacing;
  // Node coordinates exactly as ScalarGrid::position() computes them, so a node's value
  // matches value(grid.position(...)).
  for (int a = 0; a < 3; ++a) {
    std::vector<double>& coords = nodes.coords[a];
    coords.resize(size_t(nodes.dims[a]));
    for (int i = 0; i < nodes.dims[a]; ++i) {
      glm::ivec3 n(0);
      n[a] = i;
      coords[size_t(i)] = grid.position(n.x, n.y, n.z)[a];
    }
    SYLVA_CHECK(std::isfinite(coords.front()) && std::isfinite(coords.back()),
                "grid nodes must be finite");
  }
  // Node ranges are found arithmetically (node i at coords[0] + i h) while the kernel uses
  // the float node coordinates. Where float rounding moves nodes by more than 1e-4 rho (a
  // grid far from the origin for its spacing, or a rho below the rounding), the ranges grow
  // by that many nodes so that no node within rho is missed; otherwise a missed rim node
  // would add at most (2e-4)^2.
  const double h = nodes.h;
  double drift = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < nodes.dims[a]; ++i)
      drift = std::max(drift,
                       std::abs(nodes.coords[a][size_t(i)] - (nodes.coords[a][0] + h * double(i))));
  nodes.widen = drift <= 1e-4 * rho ? 0.0 : std::ceil(std::min(drift / h, double(1 << 30))) + 1.0;
  return nodes;
}

std::vector<NodeBox> node_boxes(const std::vector<glm::vec3>& gens, const GridNodes& nodes,
                                double rho) {
  const double h = nodes.h;
  const double rho_nodes = rho / h;
  const double widen = nodes.widen;
  const int64_t count = int64_t(gens.size());
  std::vector<NodeBox> boxes(static_cast<size_t>(count));
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < count; ++i) {
    NodeBox box;
    bool near = true;
    for (int a = 0; a < 3; ++a) {
      const double g = (double(gens[size_t(i)][a]) - nodes.coords[a][0]) / h;
      const double lo = g - rho_nodes - 1.0 - widen, hi = g + rho_nodes + 1.0 + widen;
      near = hi >= 0.0 && lo <= double(nodes.dims[a] - 1);
      if (!near) break;
      box.lo[a] = int(std::ceil(std::max(lo, 0.0)));
      box.hi[a] = int(std::floor(std::min(hi, double(nodes.dims[a] - 1))));
    }
    boxes[size_t(i)] = near ? box : NodeBox{};
  }
  return boxes;
}

Slabs slab_generators(const std::vector<NodeBox>& boxes, const GridNodes& nodes) {
  const int nz = nodes.dims[2];
  Slabs out;
  const int slab = std::clamp(int(std::min<size_t>(8, (size_t(1) << 20) / nodes.plane)), 1,
                              std::max(1, std::min(8, nz / 16)));
  const int slabs = (nz + slab - 1) / slab;
  out.slab = slab;
  out.count = slabs;
  // Generators of each slab, in generator order (counting sort).
  std::vector<size_t>& slab_start = out.start;
  slab_start.assign(size_t(slabs) + 1, 0);
  for (const NodeBox& b : boxes)
    if (touches(b))
      for (int s = b.lo[2] / slab; s <= b.hi[2] / slab; ++s)
        ++slab_start[size_t(s) + 1];
  for (int s = 0; s < slabs; ++s)
    slab_start[size_t(s) + 1] += slab_start[size_t(s)];
  out.gens.resize(slab_start.back());
  std::vector<size_t> fill(slab_start.begin(), slab_start.end() - 1);
  for (size_t i = 0; i < boxes.size(); ++i) {
    const NodeBox& b = boxes[i];
    if (touches(b))
      for (int s = b.lo[2] / slab; s <= b.hi[2] / slab; ++s)
        out.gens[fill[size_t(s)]++] = uint32_t(i);
  }
  return out;
}

void splat_slabs(const std::vector<glm::vec3>& gens, const std::vector<NodeBox>& boxes,
                 const Slabs& slabs, const GridNodes& nodes, double rho, double tau,
                 ScalarGrid& grid) {
  const double inv_r2 = 1.0 / (rho * rho);
  const double rho_nodes = rho / nodes.h;
  const int nz = nodes.dims[2];
#pragma omp parallel
  {
    SlabScratch scratch(nodes, slabs.slab);
#pragma omp for schedule(dynamic, 1)
    for (int s = 0; s < slabs.count; ++s) {
      const int z_begin = s * slabs.slab, z_end = std::min(nz, z_begin + slabs.slab);
      std::fill(scratch.acc.begin(), scratch.acc.end(), 0.0);
      for (size_t k = slabs.start[size_t(s)]; k < slabs.start[size_t(s) + 1]; ++k) {
        const uint32_t gi = slabs.gens[k];
        splat_generator(gens[gi], boxes[gi], z_begin, z_end, nodes, inv_r2, rho_nodes, scratch);
      }
      write_slab(scratch.acc, z_begin, z_end, nodes.plane, tau, grid);
    }
  }
}

}  // namespace sylva::density_splat
