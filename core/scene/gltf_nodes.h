// The node tree of a glTF file (used by gltf_read.cpp): composes transforms, finds the
// plants (a subtree that occurs more than once with the same meshes under the same relative
// transforms, or whose root node's extras say "sylva_plant": true or "<plant name>"; a mesh
// drawn with EXT_mesh_gpu_instancing) and their instances, and where every other mesh and every
// camera sits in the world. A group of fewer than kMinPlantTriangles triangles (a leaf card, a
// blade, a needle tuft repeated inside a plant) is a part of the plant around it, not a plant:
// it is placed once per occurrence like any other mesh. Malformed trees and instancing data
// throw InputError(path, ...).
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene/gltf_accessor.h"
#include "core/scene/scene.h"

namespace sylva {

inline constexpr size_t kMinPlantTriangles = 100;
inline constexpr size_t kMaxInstances = size_t(1) << 20;  // 1,048,576 per file

// A glTF mesh placed by a node: its primitives go into the scene transformed by `transform`
// (mesh space -> plant space, or world space outside plants).
struct MeshPlacement {
  int mesh = -1;
  int node = -1;
  glm::dmat4 transform{1.0};
};

struct PlantPlan {
  std::string name;
  int root_node = -1;  // -1: the meshes outside every plant (world space)
  std::vector<MeshPlacement> meshes;
};

struct InstancePlan {
  size_t plant = 0;  // index into NodePlan::plants
  glm::dmat4 world{1.0};
  std::string name;
};

struct CameraPlacement {
  int camera = -1;
  int node = -1;
  glm::dmat4 world{1.0};
};

// plants[0] holds the meshes outside every plant (world space, possibly none). With no other
// plant the scene is flat: plants[0] is all there is, in the order of a pre-order walk.
struct NodePlan {
  std::vector<PlantPlan> plants;
  std::vector<InstancePlan> instances;   // of plants 1, 2, ...
  std::vector<CameraPlacement> cameras;  // in the walk's order
  bool instanced() const { return plants.size() > 1; }
};

// `json` is the file's raw JSON (for extras and extensions). Reads the instancing accessors
// through `accessors`.
NodePlan plan_nodes(const std::string& path, const tinygltf::Model& model,
                    const nlohmann::json& json, const GltfAccessorReader& accessors);

// A node's local matrix (matrix, or translation * rotation * scale).
glm::dmat4 node_matrix(const tinygltf::Node& node);

}  // namespace sylva
