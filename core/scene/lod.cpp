#include "core/scene/lod.h"

namespace sylva {

Mesh lod_as_mesh(const Mesh& source, const LodMesh& lod) {
  Mesh m;
  m.name = source.name;
  m.material = source.material;
  m.outward_normals = source.outward_normals;
  m.positions = lod.positions;
  m.normals = gather(source.normals, lod.source);
  m.uvs = gather(source.uvs, lod.source);
  m.colors = gather(source.colors, lod.source);
  m.ka = gather(source.ka, lod.source);
  m.indices = lod.indices;
  m.primitive_ids = gather(source.primitive_ids, lod.triangle_source);
  m.cluster_ids = gather(source.cluster_ids, lod.triangle_source);
  m.roles = gather(source.roles, lod.triangle_source);
  return m;
}

}  // namespace sylva
