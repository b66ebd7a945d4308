#include "core/scene/mesh_read.h"

#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/scene/load.h"
#include "core/scene/mesh_formats.h"

namespace sylva {
namespace {

bool finite(const glm::vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

MeshData read_format(const std::string& path, const std::string& ext) {
  const std::string bytes = read_file_bytes(path);
  if (ext == ".obj") return read_obj(bytes, path);
  if (ext == ".off") return read_off(bytes, path);
  if (ext == ".ply") return read_ply(bytes, path);
  return read_stl(bytes, path);
}

Mesh to_mesh(MeshData&& d, const std::string& path) {
  for (size_t i = 0; i < d.positions.size(); ++i)
    if (!finite(d.positions[i]))
      throw InputError(path, "vertex " + std::to_string(i + 1) + " has a NaN or infinite position");
  for (size_t i = 0; i < d.uvs.size(); ++i)
    if (!std::isfinite(d.uvs[i].x) || !std::isfinite(d.uvs[i].y))
      throw InputError(
          path, "vertex " + std::to_string(i + 1) + " has a NaN or infinite texture coordinate");
  Mesh mesh;
  mesh.name = std::filesystem::path(path).stem().string();
  mesh.positions = std::move(d.positions);
  mesh.normals = std::move(d.normals);  // repaired in finish_scene where bad
  mesh.uvs = std::move(d.uvs);
  mesh.colors = std::move(d.colors);
  mesh.indices = std::move(d.indices);
  if (mesh.normals.empty()) compute_vertex_normals(mesh);
  mesh.material = 0;
  return mesh;
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

  MeshData data = read_format(path, ext);
  if (data.indices.empty()) {
    const std::string why = !data.first_skip.empty() ? data.first_skip
                            : data.warnings.empty()  ? ""
                                                     : data.warnings.front();
    throw InputError(path, "the file has no faces" + (why.empty() ? "" : " (" + why + ")"));
  }
  Scene scene;
  scene.report.source = path;
  if (data.skipped_faces > 0)
    scene.report.warn("faces", "skipped " + std::to_string(data.skipped_faces) +
                                   " face(s) that cannot be drawn, the first at " +
                                   data.first_skip);
  for (const std::string& w : data.warnings)
    scene.report.warn("reader", w);
  Material mat;
  mat.name = "default";
  mat.base_color = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  scene.materials.push_back(mat);
  scene.meshes.push_back(to_mesh(std::move(data), path));
  return scene;
}

}  // namespace sylva
