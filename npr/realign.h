// Normal realignment (Luft et al. §3.3): each foliage vertex takes the normal N_s of its
// nearest implicit-surface vertex (kd-tree, nanoflann), blended with its own normal
// N' = normalize((1 - blend) N + blend N_s).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "npr/implicit_surface.h"

namespace sylva {

// For each point, the normal of the nearest surface vertex (ties: the lower index). The
// surface must have as many unit normals as positions and at least one vertex.
// Parallel and deterministic.
std::vector<glm::vec3> nearest_surface_normals(const SurfaceMesh& surface,
                                               const std::vector<glm::vec3>& points);

// N' = normalize((1 - blend) n + blend ns), blend in [0, 1] (checked by the caller). When the
// sum vanishes (opposite normals at blend 0.5) or is not finite, returns ns, and n if ns is
// not usable either; the result is always unit length and finite.
glm::vec3 blend_normal(const glm::vec3& n, const glm::vec3& ns, float blend);

}  // namespace sylva
