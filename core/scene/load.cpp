#include "core/scene/load.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/scene/components.h"
#include "core/scene/foliage.h"
#include "core/scene/gltf_read.h"
#include "core/scene/instances.h"
#include "core/scene/mesh_read.h"

namespace fs = std::filesystem;

namespace sylva {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string mesh_where(const Mesh& mesh, size_t index) {
  return "mesh " + std::to_string(index) + (mesh.name.empty() ? "" : " '" + mesh.name + "'");
}

// Checks what a loader or an in-memory builder may get wrong; all of it is bad input.
void validate(const Scene& scene, const std::string& where) {
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& tex = scene.textures[t];
    if (tex.width < 0 || tex.height < 0 ||
        tex.rgba.size() != size_t(tex.width) * size_t(tex.height) * 4)
      throw InputError(where, "texture " + std::to_string(t) + " has the wrong pixel count");
  }
  for (const Material& mat : scene.materials) {
    if (mat.base_color_texture < -1 || mat.base_color_texture >= int(scene.textures.size()))
      throw InputError(where, "material '" + mat.name + "' refers to a missing texture");
  }
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const size_t nv = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
      throw InputError(where, mesh_where(mesh, m) + ": index count is not a multiple of 3");
    if (mesh.material < -1 || mesh.material >= int(scene.materials.size()))
      throw InputError(where, mesh_where(mesh, m) + ": material index out of range");
    for (const glm::vec3& p : mesh.positions)
      if (!finite(p)) throw InputError(where, mesh_where(mesh, m) + ": NaN or infinite position");
    for (uint32_t i : mesh.indices)
      if (i >= nv)
        throw InputError(where, mesh_where(mesh, m) + ": vertex index " + std::to_string(i) +
                                    " out of range (" + std::to_string(nv) + " vertices)");
    if (!mesh.uvs.empty() && mesh.uvs.size() != nv)
      throw InputError(where, mesh_where(mesh, m) + ": texture coordinate count != vertex count");
    if (!mesh.colors.empty() && mesh.colors.size() != nv)
      throw InputError(where, mesh_where(mesh, m) + ": colour count != vertex count");
    if (!mesh.ka.empty() && mesh.ka.size() != nv)
      throw InputError(where, mesh_where(mesh, m) + ": ambient coefficient count != vertex count");
    for (float ka : mesh.ka)
      if (!(ka >= 0.0f && ka <= 1.0f))
        throw InputError(where, mesh_where(mesh, m) + ": ambient coefficient outside [0, 1]");
  }
}

// Zero-area triangles break face normals and ID coverage; a relative threshold keeps tiny
// but real leaves of small-scale models.
// The threshold of each mesh: from the whole scene's bounds, or in an instanced scene from its
// plant's own (plant space), so a plant's triangles do not depend on the park around it.
std::vector<double> min_areas(const Scene& scene) {
  std::vector<double> out(scene.meshes.size(), 0.0);
  for (size_t p = 0; p < scene.plant_count(); ++p) {
    const std::vector<uint32_t> meshes = plant_meshes(scene, p);
    Bounds b;
    if (!scene.instanced()) b = scene.bounds();
    for (uint32_t mi : meshes)
      if (scene.instanced())
        for (uint32_t i : scene.meshes[mi].indices)
          b.extend(scene.meshes[mi].positions[i]);
    const float diag = b.diagonal();
    for (uint32_t mi : meshes)
      out[mi] = 1e-12 * double(diag) * double(diag);
  }
  return out;
}

size_t drop_degenerate(Scene& scene) {
  const std::vector<double> areas = min_areas(scene);
  size_t dropped = 0;
  for (Mesh& mesh : scene.meshes) {
    const double min_area = areas[size_t(&mesh - scene.meshes.data())];
    const size_t n = mesh.triangle_count();
    const bool has_roles = mesh.roles.size() == n;
    size_t out = 0;
    for (size_t t = 0; t < n; ++t) {
      const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1],
                     c = mesh.indices[3 * t + 2];
      const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
      const double area = 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
      if (a == b || b == c || a == c || !(area >= min_area) || area == 0.0) {
        ++dropped;
        continue;
      }
      mesh.indices[3 * out] = a;
      mesh.indices[3 * out + 1] = b;
      mesh.indices[3 * out + 2] = c;
      if (has_roles) mesh.roles[out] = mesh.roles[t];
      ++out;
    }
    mesh.indices.resize(3 * out);
    if (has_roles)
      mesh.roles.resize(out);
    else
      mesh.roles.clear();
  }
  std::vector<char> keep(scene.meshes.size());
  for (size_t m = 0; m < keep.size(); ++m)
    keep[m] = !scene.meshes[m].indices.empty();
  remove_meshes(scene, keep);
  return dropped;
}

// Non-finite or zero normals fall back to the surrounding faces' normal; all become unit.
void repair_normals(Mesh& mesh) {
  if (mesh.normals.size() != mesh.positions.size()) {
    compute_vertex_normals(mesh);
    return;
  }
  auto usable = [](const glm::vec3& n) {
    const double len = glm::length(glm::dvec3(n));
    return std::isfinite(len) && len > 1e-12;
  };
  bool bad = false;
  for (const glm::vec3& n : mesh.normals)
    bad = bad || !usable(n);
  std::vector<glm::vec3> fallback;
  if (bad) {
    Mesh copy;
    copy.positions = mesh.positions;
    copy.indices = mesh.indices;
    compute_vertex_normals(copy);
    fallback = std::move(copy.normals);
  }
  for (size_t v = 0; v < mesh.normals.size(); ++v) {
    glm::vec3& n = mesh.normals[v];
    n = usable(n) ? glm::vec3(glm::normalize(glm::dvec3(n))) : fallback[v];
  }
}

std::string lower(std::string s) {
  for (char& c : s)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

void compute_vertex_normals(Mesh& mesh) {
  std::vector<glm::dvec3> acc(mesh.positions.size(), glm::dvec3(0.0));
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1],
                   c = mesh.indices[3 * t + 2];
    if (a >= acc.size() || b >= acc.size() || c >= acc.size()) continue;
    const glm::dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]), pc(mesh.positions[c]);
    // The cross product's length is twice the area: area weighting for free.
    const glm::dvec3 n = glm::cross(pb - pa, pc - pa);
    acc[a] += n;
    acc[b] += n;
    acc[c] += n;
  }
  mesh.normals.resize(acc.size());
  for (size_t v = 0; v < acc.size(); ++v) {
    const double len = glm::length(acc[v]);
    mesh.normals[v] =
        len > 0.0 && std::isfinite(len) ? glm::vec3(acc[v] / len) : glm::vec3(0, 0, 1);
  }
}

void validate_hierarchy(const Hierarchy& h, const std::string& where) {
  const size_t n = h.branch_parent.size();
  if (h.branch_diameter.size() != n)
    throw InputError(where, "sylva_hierarchy: branch_parent has " + std::to_string(n) +
                                " entries but branch_diameter has " +
                                std::to_string(h.branch_diameter.size()));
  if (n == 0 && !h.leaf_branch.empty())
    throw InputError(where, "sylva_hierarchy: leaf_branch given without branches");
  for (size_t b = 0; b < n; ++b) {
    const int32_t p = h.branch_parent[b];
    if (p < -1 || p >= int32_t(n) || p == int32_t(b))
      throw InputError(where, "sylva_hierarchy: branch_parent[" + std::to_string(b) +
                                  "] = " + std::to_string(p) + " is not in [-1, " +
                                  std::to_string(n) + ") or is the branch itself");
    const float d = h.branch_diameter[b];
    if (!std::isfinite(d) || d < 0.0f)
      throw InputError(where, "sylva_hierarchy: branch_diameter[" + std::to_string(b) +
                                  "] must be finite and >= 0");
  }
  // A parent chain longer than the branch count has a cycle.
  std::vector<uint8_t> state(n, 0);  // 0 unknown, 1 on the current walk, 2 reaches a root
  for (size_t b = 0; b < n; ++b) {
    std::vector<size_t> walk;
    int32_t cur = int32_t(b);
    while (cur != -1 && state[size_t(cur)] == 0) {
      state[size_t(cur)] = 1;
      walk.push_back(size_t(cur));
      cur = h.branch_parent[size_t(cur)];
    }
    if (cur != -1 && state[size_t(cur)] == 1)
      throw InputError(where, "sylva_hierarchy: branch_parent has a cycle through branch " +
                                  std::to_string(cur));
    for (size_t w : walk)
      state[w] = 2;
  }
  for (size_t l = 0; l < h.leaf_branch.size(); ++l) {
    const int32_t b = h.leaf_branch[l];
    if (b < 0 || b >= int32_t(n))
      throw InputError(where, "sylva_hierarchy: leaf_branch[" + std::to_string(l) + "] = " +
                                  std::to_string(b) + " is not in [0, " + std::to_string(n) + ")");
  }
}

void finish_scene(Scene& scene, const LoadOptions& options, bool keep_roles) {
  const std::string where = scene.report.source.empty() ? "scene" : scene.report.source;
  validate(scene, where);
  validate_hierarchy(scene.hierarchy, where);
  validate_instances(scene, where);
  for (const Plant& plant : scene.plants)
    validate_hierarchy(plant.hierarchy, where);
  scene.report.dropped_degenerate += drop_degenerate(scene);
  if (scene.triangle_count() == 0)
    throw InputError(where, scene.report.dropped_degenerate > 0
                                ? "no triangles left after removing " +
                                      std::to_string(scene.report.dropped_degenerate) +
                                      " degenerate ones"
                                : "the scene has no triangles");
  for (Mesh& mesh : scene.meshes)
    repair_normals(mesh);

  bool all_roles = true;
  for (const Mesh& mesh : scene.meshes)
    all_roles = all_roles && mesh.roles.size() == mesh.triangle_count();
  if (!(keep_roles && all_roles)) classify_roles(scene, options.foliage);
  assign_primitive_ids(scene);
  for (Mesh& mesh : scene.meshes)
    mesh.cluster_ids.assign(mesh.triangle_count(), 1u);
}

Scene load_scene(const std::string& path, const LoadOptions& options) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(path, "no such file");
  if (fs::is_directory(st)) throw InputError(path, "is a directory, expected a scene file");
  const std::string ext = lower(fs::path(path).extension().string());
  Scene scene;
  const bool gltf = ext == ".gltf" || ext == ".glb";
  const bool mesh = ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
  if (!gltf && !mesh)
    throw InputError(
        path, "unknown extension '" + ext + "'; allowed: .gltf, .glb, .obj, .ply, .off, .stl");
  if (!fs::is_regular_file(st)) throw InputError(path, "not a regular file");
  if (fs::file_size(path, ec) == 0 && !ec) throw InputError(path, "empty file");
  scene = gltf ? read_gltf(path) : read_mesh_file(path);
  scene.report.source = path;
  finish_scene(scene, options);
  return scene;
}

}  // namespace sylva
