// The stages of DensityField::fill_grid (npr/density_field.h): the metaball field of Luft et
// al. Eq. 2 and 3 splatted generator by generator onto the nodes of a ScalarGrid, in slabs of
// whole z planes filled in parallel. Every node sums its generators in generator order, so the
// bytes do not depend on the slab size or the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "npr/scalar_grid.h"

namespace sylva::density_splat {

// A grid's nodes along each axis, and the slack float rounding of their positions asks for.
struct GridNodes {
  int dims[3] = {1, 1, 1};
  size_t plane = 1;               // nodes per z plane
  std::vector<double> coords[3];  // node coordinates per axis, as ScalarGrid::position() gives
  double h = 1.0;                 // node spacing, scene units
  double widen = 0.0;             // nodes added around each generator's reach for node drift
};

// The nodes of `grid` (its dims, origin and spacing set) for a kernel of radius rho (scene
// units, > 0). Checks that the nodes are finite.
GridNodes grid_nodes(const ScalarGrid& grid, double rho);

// Nodes a generator may reach along each axis (one node of slack for rounding; the kernel
// itself decides), empty when lo > hi.
struct NodeBox {
  int lo[3] = {1, 1, 1};
  int hi[3] = {0, 0, 0};
};

// Each generator's NodeBox (empty for a generator out of reach of the grid), in parallel.
std::vector<NodeBox> node_boxes(const std::vector<glm::vec3>& gens, const GridNodes& nodes,
                                double rho);

// The generators each slab of z planes must sum, in generator order.
struct Slabs {
  int slab = 1;                // z planes per slab
  int count = 0;               // slabs
  std::vector<size_t> start;   // first entry of each slab in `gens`, count + 1 entries
  std::vector<uint32_t> gens;  // generator indices, slab by slab
};

// Chooses the slab size (about 2^20 nodes, at most 8 planes) and lists each slab's generators
// (counting sort over the boxes' z ranges).
Slabs slab_generators(const std::vector<NodeBox>& boxes, const GridNodes& nodes);

// Fills grid.values (already sized) with F = sum D_i - tau at every node, one slab per thread.
void splat_slabs(const std::vector<glm::vec3>& gens, const std::vector<NodeBox>& boxes,
                 const Slabs& slabs, const GridNodes& nodes, double rho, double tau,
                 ScalarGrid& grid);

}  // namespace sylva::density_splat
