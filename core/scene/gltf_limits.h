// Bounds on what a glTF file may declare, checked on its JSON before tinygltf builds its model
// (so a hostile file's counts are refused before any allocation in proportion to them): at most
// kMaxNodes nodes, kMaxMeshes meshes, kMaxPrimitives primitives in all, kMaxAccessors accessors
// and buffer views, kMaxItems materials, textures, images, samplers, buffers and cameras, and
// accessors of at most kMaxAccessorElements elements. Real scenes stay far below: a park of
// 4,000 instanced trees has about 4,000 nodes and a handful of meshes.
#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace sylva {

struct GltfLimits {
  static constexpr size_t kMaxNodes = size_t(1) << 20;       // 1,048,576
  static constexpr size_t kMaxMeshes = size_t(1) << 16;      // 65,536
  static constexpr size_t kMaxPrimitives = size_t(1) << 18;  // 262,144 in all meshes
  static constexpr size_t kMaxAccessors = size_t(1) << 20;   // and buffer views
  static constexpr size_t kMaxItems = size_t(1) << 16;       // materials, textures, images, ...
  static constexpr size_t kMaxAccessorElements = size_t(1) << 28;  // 268,435,456 per accessor
  static constexpr size_t kMaxDepth = 64;                          // JSON nesting
};

// One pass over the JSON text that builds nothing (nlohmann's SAX parser): the nesting depth
// (at most kMaxDepth, as tinygltf converts extras recursively), the counts of the top-level
// arrays and of all meshes' primitives. Throws InputError(path, "too many meshes: 100000 (at
// most 65536)"), "invalid JSON: ..." and the like.
void check_gltf_json(const std::string& path, const std::string& text);

// The accessors' element counts, on the parsed JSON (their number is bounded by then).
void check_gltf_limits(const std::string& path, const nlohmann::json& gltf);

}  // namespace sylva
