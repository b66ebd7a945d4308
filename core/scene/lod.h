// Levels of detail of a plant as the raster pass draws them (core/gl/rasterizer.h), made by
// npr/plant_lod.h: each level of each plant mesh is a mesh whose vertices and triangles name
// the plant mesh's vertex and triangle they come from, so every attribute (normals, uvs,
// colours, ids, roles, the Luft shading) carries over.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

inline constexpr int kLodLevels = 6;  // beyond the full meshes; each about half the last

// One plant mesh at one level.
struct LodMesh {
  std::vector<uint32_t> source;           // per vertex: the plant mesh's vertex
  std::vector<glm::vec3> positions;       // per vertex, plant space
  std::vector<uint32_t> indices;          // 3 per triangle
  std::vector<uint32_t> triangle_source;  // per triangle: the plant mesh's triangle
};

// levels[l][k]: level l + 1 of the plant's mesh k (Plant::meshes order).
struct PlantLod {
  std::vector<std::vector<LodMesh>> levels;
};

// `lod` of `source` as a mesh of its own: its positions and triangles, every other vertex
// array and the per-triangle ids and roles taken from the vertices and triangles it names.
Mesh lod_as_mesh(const Mesh& source, const LodMesh& lod);

// values[source[i]] for each i (empty stays empty).
template <class T>
std::vector<T> gather(const std::vector<T>& values, const std::vector<uint32_t>& source) {
  if (values.empty()) return {};
  std::vector<T> out;
  out.reserve(source.size());
  for (uint32_t s : source)
    out.push_back(values[s]);
  return out;
}

}  // namespace sylva
