// A Sylva mesh as an OpenMesh triangle mesh, so that OpenMesh's writers (an implementation
// nobody here wrote) can make OBJ, OFF, PLY and STL files of it: for the mesh format tests and
// the fuzz seeds. Vertex normals (normalised), uvs when the mesh has them, and the colour
// openmesh_color(v) per vertex. Header-only; the including file silences GCC 12's false
// -Wmaybe-uninitialized in OpenMesh's colour vectors before any header.
#pragma once

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "core/scene/scene.h"

namespace sylva::test {

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

inline OpenMesh::Vec3uc openmesh_color(size_t v) {
  return {uint8_t(40 + v % 200), uint8_t(160), uint8_t(v % 256)};
}

inline TriMesh openmesh_copy(const Mesh& m) {
  TriMesh tm;
  tm.request_vertex_normals();
  tm.request_vertex_texcoords2D();
  tm.request_vertex_colors();
  std::vector<TriMesh::VertexHandle> vh;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const glm::vec3 p = m.positions[v], n = glm::normalize(m.normals[v]);
    vh.push_back(tm.add_vertex(TriMesh::Point(p.x, p.y, p.z)));
    tm.set_normal(vh.back(), TriMesh::Normal(n.x, n.y, n.z));
    if (!m.uvs.empty()) tm.set_texcoord2D(vh.back(), TriMesh::TexCoord2D(m.uvs[v].x, m.uvs[v].y));
    tm.set_color(vh.back(), openmesh_color(v));
  }
  for (size_t k = 0; k + 2 < m.indices.size(); k += 3)
    tm.add_face(vh[m.indices[k]], vh[m.indices[k + 1]], vh[m.indices[k + 2]]);
  return tm;
}

}  // namespace sylva::test
