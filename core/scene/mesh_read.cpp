// OpenMesh's default-constructed colour vectors trip GCC 12's -Wmaybe-uninitialized inside the
// standard library; the warning is reported at the library's location, so it is silenced
// for the whole unit before any header is seen.
#if defined(__GNUC__) && !defined(__clang__)  // GCC only; clang has no such warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "core/scene/mesh_read.h"

// MeshIO must come before the mesh kernel headers so the readers register.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/error.h"
#include "core/scene/load.h"
#include "core/scene/openmesh_guard.h"

namespace sylva {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// OpenMesh's readers print their complaints ("[PLYReader] : ...", "ImporterT: ...") through its
// streams to std::cerr, std::clog and std::cout; while one reads, those three write into a
// buffer instead (their stream buffers are swapped: OpenMesh's own connect/disconnect leaks),
// and the text comes out in Sylva's error or as one warning per kind.
class OpenMeshMessages {
 public:
  OpenMeshMessages()
      : m_err(std::cerr.rdbuf(m_text.rdbuf())),
        m_log(std::clog.rdbuf(m_text.rdbuf())),
        m_out(std::cout.rdbuf(m_text.rdbuf())) {}
  ~OpenMeshMessages() { restore(); }
  OpenMeshMessages(const OpenMeshMessages&) = delete;
  OpenMeshMessages& operator=(const OpenMeshMessages&) = delete;
  // Restores the streams and returns the messages, one per line (blank lines dropped).
  std::vector<std::string> lines() {
    restore();
    std::vector<std::string> out;
    std::istringstream in(m_text.str());
    for (std::string line; std::getline(in, line);)
      if (line.find_first_not_of(" \t\r") != std::string::npos) out.push_back(line);
    return out;
  }

 private:
  void restore() {
    if (m_restored) return;
    omerr().flush(), omlog().flush(), omout().flush();
    std::cerr.rdbuf(m_err), std::clog.rdbuf(m_log), std::cout.rdbuf(m_out);
    m_restored = true;
  }
  std::ostringstream m_text;
  std::streambuf *m_err, *m_log, *m_out;
  bool m_restored = false;
};

bool finite(const PolyMesh::Point& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

}  // namespace

Scene read_mesh_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file");
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path, "is a directory, expected a mesh file");
  if (std::filesystem::file_size(path, ec) == 0) throw InputError(path, "empty file");

  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".ply") check_ply_header(path);

  PolyMesh pm;
  pm.request_vertex_normals();
  pm.request_vertex_texcoords2D();
  pm.request_vertex_colors();
  OpenMesh::IO::Options opt;
  opt += OpenMesh::IO::Options::VertexNormal;
  opt += OpenMesh::IO::Options::VertexTexCoord;
  opt += OpenMesh::IO::Options::VertexColor;
  bool ok = false;
  std::vector<std::string> messages;
  {
    OpenMeshMessages capture;
    try {
      // OpenMesh::IO::read_mesh, with SafeImporter (core/scene/openmesh_guard.h).
      SafeImporter<PolyMesh> importer(pm, size_t(std::filesystem::file_size(path, ec)));
      ok = OpenMesh::IO::IOManager().read(path, importer, opt);
    } catch (const std::exception& e) {
      throw InputError(path, std::string("cannot read the mesh: ") + e.what());
    }
    messages = capture.lines();
  }
  const std::string first = messages.empty() ? "" : ": OpenMesh: " + messages.front();
  if (!ok) throw InputError(path, "cannot read the mesh (OpenMesh could not parse it)" + first);
  if (pm.n_faces() == 0) throw InputError(path, "the file has no faces" + first);

  Mesh mesh;
  mesh.name = std::filesystem::path(path).stem().string();
  mesh.positions.reserve(pm.n_vertices());
  for (auto vh : pm.vertices()) {
    const PolyMesh::Point& p = pm.point(vh);
    if (!finite(p))
      throw InputError(path,
                       "vertex " + std::to_string(vh.idx()) + " has a NaN or infinite position");
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  // OpenMesh's STL reader reports vertex normals it never writes (STL has facet normals only).
  if (opt.check(OpenMesh::IO::Options::VertexNormal) && ext != ".stl") {
    for (auto vh : pm.vertices()) {
      const auto& n = pm.normal(vh);
      mesh.normals.emplace_back(n[0], n[1], n[2]);  // repaired in finish_scene if bad
    }
  }
  // Nor texture coordinates or colours, which it leaves uninitialised.
  if (opt.check(OpenMesh::IO::Options::VertexTexCoord) && ext != ".stl") {
    for (auto vh : pm.vertices()) {
      const auto& t = pm.texcoord2D(vh);
      mesh.uvs.emplace_back(t[0], t[1]);
    }
  }
  if (opt.check(OpenMesh::IO::Options::VertexColor) && ext != ".stl") {
    for (auto vh : pm.vertices()) {
      const auto& c = pm.color(vh);
      mesh.colors.emplace_back(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f);
    }
  }
  // Polygons become fans around their first vertex (leaf cards and quads are convex).
  for (auto fh : pm.faces()) {
    std::vector<uint32_t> loop;
    for (auto vh : pm.fv_range(fh))
      loop.push_back(uint32_t(vh.idx()));
    for (size_t k = 1; k + 1 < loop.size(); ++k)
      mesh.indices.insert(mesh.indices.end(), {loop[0], loop[k], loop[k + 1]});
  }
  if (mesh.normals.empty()) compute_vertex_normals(mesh);

  Scene scene;
  Material mat;
  mat.name = "default";
  mat.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  scene.materials.push_back(mat);
  mesh.material = 0;
  scene.meshes.push_back(std::move(mesh));
  scene.report.source = path;
  for (const std::string& m : messages)
    scene.report.warn("openmesh", "OpenMesh: " + m);
  return scene;
}

}  // namespace sylva
