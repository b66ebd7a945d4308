// Optional mesh optimisation of the extracted implicit surface (Luft & Balzer 2006: "an
// additional mesh optimization may be applied ... to obtain a homogeneous mesh with a lower
// number of primitives and more consistent vertex normals"): Laplacian smoothing and
// quadric-error decimation with OpenMesh. The heap-based DecimaterT is used rather than
// McDecimaterT because the latter samples with the global rand(), which would make the
// output depend on unrelated code.
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "npr/implicit_surface.h"
#include "npr/open_mesh.h"

namespace sylva {
namespace {

OpenTriMesh to_openmesh(const SurfaceMesh& in) {
  OpenTriMesh m;
  m.reserve(in.positions.size(), in.indices.size() / 2, in.triangle_count());
  std::vector<OpenTriMesh::VertexHandle> vh;
  vh.reserve(in.positions.size());
  for (const glm::vec3& p : in.positions)
    vh.push_back(m.add_vertex(OpenTriMesh::Point(p.x, p.y, p.z)));
  for (size_t t = 0; t < in.triangle_count(); ++t) {
    const uint32_t* idx = &in.indices[3 * t];
    if (idx[0] == idx[1] || idx[1] == idx[2] || idx[2] == idx[0]) continue;
    std::array<OpenTriMesh::VertexHandle, 3> f = {vh[idx[0]], vh[idx[1]], vh[idx[2]]};
    if (!can_add_face(m, f) || !m.add_face(f[0], f[1], f[2]).is_valid()) {
      for (auto& v : f)
        v = m.add_vertex(m.point(v));
      m.add_face(f[0], f[1], f[2]);
    }
  }
  return m;
}

void from_openmesh(const OpenTriMesh& m, SurfaceMesh& out) {
  out.positions.clear();
  out.indices.clear();
  out.normals.clear();
  std::vector<uint32_t> remap(m.n_vertices(), UINT32_MAX);
  for (const auto f : m.faces()) {
    for (const auto v : f.vertices()) {
      uint32_t& r = remap[size_t(v.idx())];
      if (r == UINT32_MAX) r = 0;  // marks used; numbered below in vertex order
    }
  }
  uint32_t n = 0;
  for (const auto v : m.vertices()) {
    uint32_t& r = remap[size_t(v.idx())];
    if (r == UINT32_MAX) continue;
    r = n++;
    const auto& p = m.point(v);
    const glm::vec3 q(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
    SYLVA_CHECK(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z),
                "non-finite vertex after mesh optimisation");
    out.positions.push_back(q);
  }
  out.indices.reserve(3 * m.n_faces());
  for (const auto f : m.faces()) {
    for (const auto v : f.vertices())
      out.indices.push_back(remap[size_t(v.idx())]);
  }
}

}  // namespace

void optimize_surface(SurfaceMesh& mesh, const SurfaceOptimizeOptions& options) {
  if (options.smooth_iterations < 0 || options.smooth_iterations > 100) {
    throw InputError("smooth", "smoothing iterations must be an integer in [0, 100], got " +
                                   std::to_string(options.smooth_iterations));
  }
  const double keep = options.keep_fraction;
  if (!(std::isfinite(keep) && keep > 0.0 && keep <= 1.0)) {
    throw InputError("decimate", "share of triangles kept must be a number in (0, 1], got " +
                                     std::to_string(keep));
  }
  SYLVA_CHECK(mesh.indices.size() % 3 == 0, "surface indices are not triangles");
  for (uint32_t i : mesh.indices)
    SYLVA_CHECK(i < mesh.positions.size(), "index out of range");
  mesh.normals.clear();
  if (mesh.indices.empty() || (options.smooth_iterations == 0 && keep == 1.0)) return;

  OpenTriMesh m = to_openmesh(mesh);

  if (options.smooth_iterations > 0) {
    // Uniform (umbrella) weights, full Laplacian: removes the staircase noise of marching
    // cubes; boundary vertices (where the surface leaves the grid) stay fixed.
    OpenMesh::Smoother::JacobiLaplaceSmootherT<OpenTriMesh> smoother(m);
    smoother.initialize(
        OpenMesh::Smoother::JacobiLaplaceSmootherT<OpenTriMesh>::Tangential_and_Normal,
        OpenMesh::Smoother::JacobiLaplaceSmootherT<OpenTriMesh>::C0);
    smoother.smooth(unsigned(options.smooth_iterations));
  }

  const size_t n_faces = m.n_faces();
  const size_t target = std::max<size_t>(1, size_t(std::llround(keep * double(n_faces))));
  if (target < n_faces) {
    m.request_face_normals();  // ModNormalFlippingT would log a warning and compute them
    m.update_face_normals();
    OpenMesh::Decimater::DecimaterT<OpenTriMesh> decimater(m);
    OpenMesh::Decimater::ModQuadricT<OpenTriMesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<OpenTriMesh>::Handle no_flips;
    decimater.add(quadric);
    decimater.add(no_flips);
    decimater.module(quadric).unset_max_err();  // the face count alone stops it
    // No collapse may turn a face by more than 45 degrees: keeps faces from folding over
    // (the default 90 lets a face end up edge-on to the surface it approximates).
    decimater.module(no_flips).set_max_normal_deviation(45.0);
    decimater.initialize();
    decimater.decimate_to_faces(0, target);
    m.garbage_collection();
  }

  from_openmesh(m, mesh);
}

}  // namespace sylva
