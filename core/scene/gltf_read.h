// Reading glTF 2.0 (.gltf with external or embedded buffers, .glb) into the scene model with
// tinygltf: walks the default scene's node tree composing transforms (gltf_nodes.h); a file
// without repeated subtrees or EXT_mesh_gpu_instancing becomes a flat scene (every triangle
// primitive a world-space Mesh), otherwise its plants are stored once in their own space with
// their instances, the meshes outside every plant making one more plant with one instance at
// the identity. Reads the cameras the nodes place, base-colour materials and decodes their
// textures to RGBA8, the plant hierarchy (extras "sylva_hierarchy" of the scene, or of a
// plant's root node) and per-mesh roles
// (extras "sylva_role"), and the ambient coefficient "_AMBIENT" (SCALAR, each value in [0, 1])
// into Mesh::ka; in files marked "sylva_color_0": "ambient" (gltf_write.h) COLOR_0 is only the
// ka preview, so vertex colours come from COLOR_1. The result is raw: load.h's finish_scene
// validates it further and assigns ids. Every malformed file throws
// InputError(path, "<what is wrong>").
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

// Meshes get the glTF mesh name (else the node name, else "mesh<i>"), with "[k]" appended
// for primitive k when a mesh has several. Mesh::roles is filled only for primitives whose
// primitive or mesh extras carry "sylva_role" ("foliage", "wood", "ground", "other",
// "grass"); otherwise it is left empty. primitive_ids and cluster_ids are left empty.
Scene read_gltf(const std::string& path);

}  // namespace sylva
