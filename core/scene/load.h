// Loading a scene file into the scene model: dispatch on the extension (.gltf/.glb via
// tinygltf, .obj/.ply/.off/.stl by Sylva's readers), validate (NaN/Inf, index ranges), drop
// zero-area and degenerate triangles (counted in the report), classify roles (foliage.h),
// and assign primitive ids (components.h). Cluster ids are set to 1 here and assigned
// properly by npr/leaf_clusters.h. Bad input throws InputError naming the file.
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

struct LoadOptions {
  // "auto" (name match, else alpha-MASK materials), "none", "all", or a glob matched
  // case-insensitively against material and mesh names ("*leaf*", "fern_0?").
  std::string foliage = "auto";
};

Scene load_scene(const std::string& path, const LoadOptions& options = {});

// The part of load_scene after parsing, for scenes built in memory (samples, tests):
// validation (indices, finite positions, attribute counts, material/texture references, the
// hierarchy), removal of triangles with a repeated index or an area below
// 1e-12 * bounds-diagonal^2 (counted in report.dropped_degenerate; meshes left empty are
// removed), normals computed when absent and repaired (non-finite or zero -> the adjacent
// faces' normal) and made unit length, roles (unless keep_roles and every mesh has them;
// in "auto" mode roles already present, e.g. from glTF extras, are kept), primitive ids,
// cluster ids = 1. Throws InputError(report.source or "scene", ...) on bad input or when no
// triangle is left.
void finish_scene(Scene& scene, const LoadOptions& options, bool keep_roles = false);

// Area-weighted vertex normals (unit length; (0, 0, 1) for vertices on no proper triangle).
void compute_vertex_normals(Mesh& mesh);

// Checks a plant hierarchy: equal branch array lengths, parents in [-1, branches) without
// cycles, finite non-negative diameters, leaf branches in [0, branches). Throws
// InputError(where, ...) otherwise. An empty hierarchy is valid.
void validate_hierarchy(const Hierarchy& hierarchy, const std::string& where);

}  // namespace sylva
