// The OpenMesh triangle mesh the decimating passes build (npr/surface_optimize.cpp for the
// implicit surface, npr/plant_lod.cpp for levels of detail): double-precision points and
// normals, and the test that keeps add_face() from refusing (and logging) a face.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <array>
#include <cstddef>

namespace sylva {

struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OpenTriMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

// Whether add_face() takes the face: it refuses faces that would make an edge or a vertex
// non-manifold (marching cubes makes such spots where two sheets touch at exact zeros, and a
// triangle soup has them wherever leaves share a vertex); the callers give such a face copies
// of its vertices instead.
inline bool can_add_face(const OpenTriMesh& m, const std::array<OpenTriMesh::VertexHandle, 3>& v) {
  for (size_t i = 0; i < 3; ++i) {
    if (!m.is_boundary(v[i])) return false;  // isolated vertices count as boundary
    const auto he = m.find_halfedge(v[i], v[(i + 1) % 3]);
    if (he.is_valid() && !m.is_boundary(he)) return false;
  }
  return true;
}

}  // namespace sylva
