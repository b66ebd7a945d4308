// The levels of detail of an instanced scene's plants on the GPU (core/gl/rasterizer.h's
// set_lod): a GpuMesh per plant, level and plant mesh, made from the plant mesh with the
// vertices and triangles the level names (core/scene/lod.h), and the Luft shading carried over
// through the same vertex sources. Runs in the current GL context; release() before it goes.
#pragma once

#include <cstdint>
#include <vector>

#include "core/gl/gpu_scene.h"
#include "core/gl/rasterizer.h"
#include "core/scene/lod.h"

namespace sylva {

class LodMeshes {
 public:
  // Uploads every level of every plant (one PlantLod per plant of `scene`).
  void upload(const Scene& scene, const std::vector<PlantLod>& lods);
  void release();
  // The uploaded meshes of plant p at level l (1 .. kLodLevels).
  const std::vector<size_t>& of(size_t plant, int level) const {
    return m_plant_meshes[plant][size_t(level - 1)];
  }
  const std::vector<GpuMesh>& meshes() const { return m_meshes; }
  // Replaces the levels' normals and ka with those of their scene meshes in `shading`.
  void set_shading(const VertexShading& shading);

 private:
  std::vector<GpuMesh> m_meshes;
  std::vector<std::vector<std::vector<size_t>>> m_plant_meshes;  // [plant][level - 1]
  std::vector<std::vector<uint32_t>> m_sources;                  // per mesh: vertex sources
};

}  // namespace sylva
