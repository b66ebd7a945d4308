// The instances of an instanced scene for the raster pass (core/gl/rasterizer.h): each
// plant's meshes are uploaded once and drawn with glDrawElementsInstanced over a buffer of
// per-instance records (transform, normal matrix, id bases; the INSTANCED shader variant,
// core/gl/shaders.h). Per render, instances whose bounding sphere lies wholly outside the
// camera's view volume are left out (they cover no pixel), each other one gets the level of
// detail its projected size asks for (when levels are set), and mirrored instances are drawn
// in batches of their own with the front face reversed. Runs in the current GL context.
#pragma once

#include "core/gl/gl_api.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/gl/camera.h"
#include "core/scene/instances.h"
#include "core/scene/scene.h"

namespace sylva {

// Level of detail: an instance is drawn at the coarsest level (each about half the triangles
// of the one before, core/scene/lod.h) that still has no more than this many
// triangles per pixel of its bounding sphere's projected disc (render size x supersampling).
inline constexpr double kLodTrianglesPerPixel = 1.0;

// One draw's instances: `count` records of one plant at one level of detail from byte
// `offset` of the buffer.
struct InstanceBatch {
  uint32_t plant = 0;
  int level = 0;  // 0 = the full meshes
  GLintptr offset = 0;
  GLsizei count = 0;
  bool mirrored = false;  // the transform's determinant is negative: front faces are CW
};

// The sphere around the instances `camera` sees (their plants' bounding spheres, ground left
// out, moved by their transforms), for fitting a shadow map to what the picture shows; empty
// when the scene is flat or no instance is in view.
Sphere visible_instances_sphere(const Scene& scene, const Camera& camera);

class InstanceDraws {
 public:
  // The owner calls release() while the GL context is current; destruction frees nothing.
  InstanceDraws() = default;
  ~InstanceDraws() = default;
  InstanceDraws(const InstanceDraws&) = delete;
  InstanceDraws& operator=(const InstanceDraws&) = delete;

  // Keeps the transforms, id bases (IdLayout) and each plant's bounding sphere (plant space).
  // A flat scene keeps nothing: instanced() is then false.
  void upload(const Scene& scene);
  void release();
  bool instanced() const { return !m_records.empty(); }
  uint32_t branch_cluster() const { return m_branch_cluster; }
  size_t plant_count() const { return m_spheres.size(); }

  // Levels of detail to choose from: per plant, its triangle count (the full meshes) and how
  // many coarser levels it has (0 = none). Not called: every instance is drawn whole.
  void set_levels(const std::vector<size_t>& plant_triangles, const std::vector<int>& levels);

  // Fills the buffer with the instances `camera` can see and returns their batches, plant by
  // plant in scene order, by level, unmirrored first; `drawn` receives how many instances are
  // drawn. `ssaa` scales the pixel counts of the level choice.
  std::vector<InstanceBatch> prepare(const Camera& camera, int ssaa = 1, size_t* drawn = nullptr);
  // Points the per-instance attributes of the bound vertex array at `batch`'s records.
  void bind(const InstanceBatch& batch) const;

 private:
  // Instance i's level at world centre `centre` and radius `radius`.
  int level_of(size_t i, const glm::vec3& centre, float radius, const Camera& camera,
               int ssaa) const;

  struct Record {
    glm::vec4 model[4];
    glm::vec4 normal[3];  // the normal matrix's columns (w unused)
    glm::uvec4 ids;       // primitive, cluster, object bases; the plant
  };
  std::vector<Record> m_records;     // per scene instance
  std::vector<uint32_t> m_plant;     // per scene instance
  std::vector<bool> m_mirrored;      // per scene instance
  std::vector<glm::vec4> m_spheres;  // per plant: centre, radius (plant space)
  std::vector<size_t> m_triangles;   // per plant, for the level choice (empty: no levels)
  std::vector<int> m_levels;         // per plant: coarser levels available
  uint32_t m_branch_cluster = 0;
  GLuint m_buffer = 0;
  size_t m_capacity = 0;  // records the buffer holds
};

}  // namespace sylva
