// What the polygon mesh readers (obj_read, off_read, ply_read, stl_read; dispatched by
// mesh_read.cpp) produce: one vertex per position, optional per-vertex normals, texture
// coordinates and colours, and triangles. Polygons are fan-triangulated around their first
// vertex (leaf cards and quads are convex). A face with fewer than three vertices or a vertex
// index out of range is skipped and counted; mesh_read turns the count into one warning (the
// OBJ reader refuses such a face instead: its indices name what was declared before them).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {

struct MeshData {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty, or one per position
  std::vector<glm::vec2> uvs;      // empty, or one per position
  std::vector<glm::vec4> colors;   // empty, or one per position, in [0, 1]
  std::vector<uint32_t> indices;   // 3 per triangle
  size_t skipped_faces = 0;
  std::string first_skip;             // where and why the first skipped face was skipped
  std::vector<std::string> warnings;  // the reader's own

  // Adds polygon v[0..n) over `vertex_count` vertices, or counts it as skipped; `where` names
  // it for the warning ("line 12", "face 7"), which shows indices counted from `base` (OBJ: 1).
  // A face's index that is out of range must arrive as one (>= vertex_count).
  template <class Where>
  void add_polygon(const uint32_t* v, size_t n, size_t vertex_count, Where&& where,
                   uint64_t base = 0) {
    std::string why;
    if (n < 3) why = "has " + std::to_string(n) + " vertices";
    for (size_t k = 0; k < n && why.empty(); ++k)
      if (v[k] >= vertex_count)
        why = "has vertex index " + std::to_string(v[k] + base) + " out of range (" +
              std::to_string(vertex_count) + " vertices)";
    if (!why.empty()) {
      if (skipped_faces++ == 0) first_skip = where() + ": the face " + why;
      return;
    }
    for (size_t k = 1; k + 1 < n; ++k)
      indices.insert(indices.end(), {v[0], v[k], v[k + 1]});
  }
};

// A colour channel read from a file, clamped to [0, 1]; NaN is an error.
inline float unit_channel(double c, const std::string& path, const std::string& where) {
  if (c != c) throw InputError(path, where + ": a colour is not a number");
  return float(c < 0.0 ? 0.0 : c > 1.0 ? 1.0 : c);
}

}  // namespace sylva
