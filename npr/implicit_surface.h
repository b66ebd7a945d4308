// Polygonising the implicit surface F = 0 (Luft et al. §3.1) from a sampled density grid
// by marching cubes, and the optional mesh optimisation of the tech report (Luft & Balzer
// 2006: smoothing and decimation with OpenMesh).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "npr/scalar_grid.h"

namespace sylva {

struct SurfaceMesh {
  std::vector<glm::vec3> positions;  // scene units
  std::vector<glm::vec3> normals;    // unit, outward; filled by the caller (e.g. -grad F)
  std::vector<uint32_t> indices;     // triangles, counter-clockwise seen from outside (F < 0)
  size_t triangle_count() const { return indices.size() / 3; }
};

// Zero level set of grid.values, inside where value > 0. Vertices are shared between
// neighbouring cells (an indexed, watertight mesh where the surface does not leave the
// grid), placed by linear interpolation along cell edges; no degenerate triangles.
// normals are left empty. Empty mesh when no cell changes sign.
SurfaceMesh extract_isosurface(const ScalarGrid& grid);

struct SurfaceOptimizeOptions {
  int smooth_iterations = 0;  // Laplacian smoothing passes, [0, 100]
  double keep_fraction = 1;   // decimation target: share of triangles kept, (0, 1]
};

// Smooths and/or decimates in place (OpenMesh); normals are cleared (the caller
// recomputes them). Throws InputError on out-of-range options.
void optimize_surface(SurfaceMesh& mesh, const SurfaceOptimizeOptions& options);

}  // namespace sylva
