// Instanced scenes (Scene::plants, Scene::instances): how an instance's ids are laid out in
// the id buffer, a plant as a scene of its own (what every per-plant computation runs on),
// flattening an instanced scene into world-space meshes, and the invariants the loader and
// the in-memory builders must keep.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

// What instance i adds to its plant's own ids in the id buffer.
struct InstanceIdBase {
  uint32_t primitive = 0;
  uint32_t cluster = 0;  // foliage clusters only; see IdLayout::branch_cluster
  uint32_t object = 0;
};

// The id buffer of an instanced scene: instance i's primitive ids, foliage cluster ids and
// object ids (its plant's mesh index + 1) are its plant's own plus bases[i], each base being
// the sum of the largest such id of the instances before it (scene order), so every instance
// has its own ids and they stay dense. Non-foliage triangles of every instance (trunks,
// branches, ground) share the one cluster id branch_cluster (the sum of all instances'
// foliage clusters + 1), as the non-foliage of one plant shares one cluster
// (npr/leaf_clusters.h). A flat scene has one zero base and branch_cluster 0 (no remapping):
// its ids are the meshes' own.
struct IdLayout {
  std::vector<InstanceIdBase> bases;  // per instance (Scene::instance_count())
  uint32_t branch_cluster = 0;        // 0 = no remapping (a flat scene, or no non-foliage)
  uint32_t max_primitive = 0, max_cluster = 0, max_object = 0;  // the largest ids drawn
};
// Throws InputError("scene", ...) when an id would pass 2^32 - 1.
IdLayout id_layout(const Scene& scene);

// The meshes of plant p in order (a flat scene's one plant: every mesh).
std::vector<uint32_t> plant_meshes(const Scene& scene, size_t plant);
// The instances of plant p in scene order (a flat scene: {0}).
std::vector<uint32_t> plant_instances(const Scene& scene, size_t plant);

// Plant p as a flat scene of its own, in plant space: copies of its meshes in order, the
// scene's materials and (with `textures`) textures, its hierarchy and the scene's report
// source. Per-plant computations run on it and write their per-mesh results back through
// plant_meshes().
Scene plant_scene(const Scene& scene, size_t plant, bool textures = true);

// The scene with every instance's meshes moved into world space (positions in double as the
// glTF reader flattens nodes, normals by the inverse transpose, winding reversed under a
// mirroring transform): one mesh per instance and plant mesh in instance order, named
// "<instance>/<mesh>" when the instance has a name, with the ids the id buffer gives them
// (IdLayout); the hierarchy is kept only for a single instance. A flat scene is returned
// unchanged.
Scene flatten(const Scene& scene);

// An instance transform's normal matrix (inverse transpose of its upper 3x3).
glm::mat3 normal_matrix(const glm::mat4& transform);

// Checks what an instanced scene must hold: every mesh in exactly one plant, plant mesh lists
// ascending, no empty plant, instance plants in range, transforms finite with a determinant
// whose magnitude is at least 1e-12 (times the scale of the matrix cubed). Throws
// InputError(where, ...). A flat scene must have no instances.
void validate_instances(const Scene& scene, const std::string& where);

// Removes the meshes with keep[m] == 0, renumbering the plants' mesh lists; plants left empty
// are removed with their instances.
void remove_meshes(Scene& scene, const std::vector<char>& keep);

}  // namespace sylva
