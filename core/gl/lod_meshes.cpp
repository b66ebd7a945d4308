#include "core/gl/lod_meshes.h"

#include <string>

#include "core/error.h"

namespace sylva {

void LodMeshes::upload(const Scene& scene, const std::vector<PlantLod>& lods) {
  release();
  SYLVA_CHECK(lods.size() == scene.plants.size(), "set_lod: one PlantLod per plant");
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const Plant& plant = scene.plants[p];
    m_plant_meshes.emplace_back();
    for (const std::vector<LodMesh>& level : lods[p].levels) {
      SYLVA_CHECK(level.size() == plant.meshes.size(), "set_lod: one LodMesh per plant mesh");
      m_plant_meshes.back().emplace_back();
      for (size_t k = 0; k < level.size(); ++k) {
        const Mesh m = lod_as_mesh(scene.meshes[plant.meshes[k]], level[k]);
        if (m.triangle_count() == 0) continue;
        m_meshes.push_back(upload_mesh(m, uint32_t(k + 1)));  // object id: as the whole mesh's
        m_meshes.back().scene_index = plant.meshes[k];
        m_sources.push_back(level[k].source);
        m_plant_meshes.back().back().push_back(m_meshes.size() - 1);
      }
    }
  }
}

void LodMeshes::release() {
  for (GpuMesh& m : m_meshes)
    release_mesh(m);
  m_meshes.clear();
  m_plant_meshes.clear();
  m_sources.clear();
}

void LodMeshes::set_shading(const VertexShading& shading) {
  static const std::vector<float> kNone;
  for (size_t k = 0; k < m_meshes.size(); ++k) {
    GpuMesh& m = m_meshes[k];
    const size_t i = m.scene_index;
    if (i >= shading.normals.size()) continue;
    replace_shading(m, gather(shading.normals[i], m_sources[k]),
                    i < shading.ka.size() ? gather(shading.ka[i], m_sources[k]) : kNone,
                    "mesh " + std::to_string(i) + " (level of detail)");
    m.oriented_foliage = shading.oriented_foliage;
  }
}

}  // namespace sylva
