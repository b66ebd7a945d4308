// The instances of an instanced scene for the raster pass (core/gl/rasterizer.h): each
// plant's meshes are uploaded once and drawn with glDrawElementsInstanced over a buffer of
// per-instance records (transform, normal matrix, id bases; the INSTANCED shader variant,
// core/gl/shaders.h). Per render, instances whose bounding sphere lies wholly outside the
// camera's view volume are left out (they cover no pixel), and mirrored instances are drawn
// in batches of their own with the front face reversed. Runs in the current GL context.
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/gl/camera.h"
#include "core/scene/instances.h"
#include "core/scene/scene.h"

namespace sylva {

// One draw's instances: `count` records of one plant from byte `offset` of the buffer.
struct InstanceBatch {
  uint32_t plant = 0;
  GLintptr offset = 0;
  GLsizei count = 0;
  bool mirrored = false;  // the transform's determinant is negative: front faces are CW
};

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

  // Fills the buffer with the instances `camera` can see and returns their batches, plant by
  // plant in scene order (unmirrored first); `drawn` receives how many instances are drawn.
  std::vector<InstanceBatch> prepare(const Camera& camera, size_t* drawn = nullptr);
  // Points the per-instance attributes of the bound vertex array at `batch`'s records.
  void bind(const InstanceBatch& batch) const;

 private:
  struct Record {
    glm::vec4 model[4];
    glm::vec4 normal[3];  // the normal matrix's columns (w unused)
    glm::uvec4 ids;       // primitive, cluster, object bases (w unused)
  };
  std::vector<Record> m_records;     // per scene instance
  std::vector<uint32_t> m_plant;     // per scene instance
  std::vector<bool> m_mirrored;      // per scene instance
  std::vector<glm::vec4> m_spheres;  // per plant: centre, radius (plant space)
  uint32_t m_branch_cluster = 0;
  GLuint m_buffer = 0;
  size_t m_capacity = 0;  // records the buffer holds
};

}  // namespace sylva
