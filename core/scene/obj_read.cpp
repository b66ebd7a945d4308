// Wavefront OBJ through tinyobjloader (Debian's libtinyobjloader-dev), parsed from the file's
// text: `mtllib` lines are not followed (materials are not used, and a path in a hostile file
// could name anything). OBJ indexes positions, texture coordinates and normals separately;
// Sylva keeps one vertex per position and takes its uv and normal from the first face corner
// that names one, so that leaves stay connected across uv seams.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <sstream>

#include "core/scene/mesh_formats.h"

namespace sylva {
namespace {

// tinyobjloader's messages, one per line, without the blank ones.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r.") != std::string::npos) out.push_back(line);
  return out;
}

struct Corners {
  std::vector<bool> has_uv, has_normal;
};

void copy_vertices(const tinyobj::attrib_t& a, MeshData& m, const std::string& path) {
  const size_t n = a.vertices.size() / 3;
  for (size_t i = 0; i < n; ++i)
    m.positions.emplace_back(a.vertices[3 * i], a.vertices[3 * i + 1], a.vertices[3 * i + 2]);
  if (a.colors.size() == 3 * n && n > 0)
    for (size_t i = 0; i < n; ++i)
      m.colors.emplace_back(
          unit_channel(a.colors[3 * i], path, "vertex " + std::to_string(i + 1)),
          unit_channel(a.colors[3 * i + 1], path, "vertex " + std::to_string(i + 1)),
          unit_channel(a.colors[3 * i + 2], path, "vertex " + std::to_string(i + 1)), 1.0f);
}

// Gives a vertex the uv and normal of the first corner that names valid ones.
void take_corner(const tinyobj::attrib_t& a, const tinyobj::index_t& c, MeshData& m, Corners& k) {
  const size_t v = size_t(c.vertex_index);
  if (c.texcoord_index >= 0 && size_t(c.texcoord_index) < a.texcoords.size() / 2 && !k.has_uv[v]) {
    m.uvs[v] = {a.texcoords[2 * c.texcoord_index], a.texcoords[2 * c.texcoord_index + 1]};
    k.has_uv[v] = true;
  }
  if (c.normal_index >= 0 && size_t(c.normal_index) < a.normals.size() / 3 && !k.has_normal[v]) {
    const float* n = &a.normals[3 * size_t(c.normal_index)];
    m.normals[v] = {n[0], n[1], n[2]};
    k.has_normal[v] = true;
  }
}

void add_faces(const tinyobj::attrib_t& a, const tinyobj::shape_t& s, MeshData& m, Corners& k) {
  std::vector<uint32_t> loop;
  size_t at = 0;
  for (size_t f = 0; f < s.mesh.num_face_vertices.size(); ++f) {
    const size_t n = s.mesh.num_face_vertices[f];
    if (n > s.mesh.indices.size() - at) break;
    loop.clear();
    for (size_t j = 0; j < n; ++j) {
      const int v = s.mesh.indices[at + j].vertex_index;
      loop.push_back(v >= 0 ? uint32_t(v) : UINT32_MAX);
    }
    const size_t before = m.indices.size();
    m.add_polygon(
        loop.data(), n, m.positions.size(),
        [&s, f] {
          return "face " + std::to_string(f + 1) + (s.name.empty() ? "" : " of '" + s.name + "'");
        },
        1);
    if (m.indices.size() > before)
      for (size_t j = 0; j < n; ++j)
        take_corner(a, s.mesh.indices[at + j], m, k);
    at += n;
  }
}

}  // namespace

MeshData read_obj(const std::string& text, const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;   // fans are made here, after every index is checked
  config.vertex_color = false;  // colours only when every vertex has them
  tinyobj::ObjReader reader;
  const bool ok = reader.ParseFromString(text, "", config);
  const std::vector<std::string> errors = lines_of(reader.Error());
  if (!ok || !errors.empty())
    throw InputError(path, "cannot read the OBJ file" +
                               (errors.empty() ? std::string() : ": " + errors.front()));
  const tinyobj::attrib_t& a = reader.GetAttrib();
  MeshData m;
  copy_vertices(a, m, path);
  m.uvs.assign(m.positions.size(), glm::vec2(0.0f));
  m.normals.assign(m.positions.size(), glm::vec3(0.0f));
  Corners k{std::vector<bool>(m.positions.size()), std::vector<bool>(m.positions.size())};
  for (const tinyobj::shape_t& s : reader.GetShapes())
    add_faces(a, s, m, k);
  if (std::find(k.has_uv.begin(), k.has_uv.end(), true) == k.has_uv.end()) m.uvs.clear();
  if (std::find(k.has_normal.begin(), k.has_normal.end(), true) == k.has_normal.end())
    m.normals.clear();
  for (const std::string& w : lines_of(reader.Warning()))  // bad indices: in the skip count
    if (w.find("indices out of bounds") == std::string::npos) m.warnings.push_back(w);
  return m;
}

}  // namespace sylva
