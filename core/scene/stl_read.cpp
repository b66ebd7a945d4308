// STL, binary (80-byte header, uint32 triangle count, 50 bytes per triangle) or ASCII
// ("solid ... facet normal ... outer loop vertex x y z ×3 endloop endfacet ... endsolid").
// STL stores every triangle's corners; corners at the same position become one vertex, so
// that a closed surface stays one connected surface. Facet normals are not used (vertex normals
// are computed from the triangles).
#include <cstring>
#include <unordered_map>

#include "core/scene/mesh_formats.h"
#include "core/scene/text_scan.h"

namespace sylva {
namespace {

// Welds corners by their exact coordinates (-0 and 0 are the same).
class Welder {
 public:
  explicit Welder(MeshData& m) : m_mesh(m) {}
  uint32_t vertex(glm::vec3 p) {
    for (int k = 0; k < 3; ++k)
      if (p[k] == 0.0f) p[k] = 0.0f;
    Key key;
    std::memcpy(key.bits, &p, sizeof key.bits);
    const auto [it, added] = m_index.try_emplace(key, uint32_t(m_mesh.positions.size()));
    if (added) m_mesh.positions.push_back(p);
    return it->second;
  }

 private:
  struct Key {
    uint32_t bits[3];
    bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      return (size_t(k.bits[0]) * 73856093u) ^ (size_t(k.bits[1]) * 19349663u) ^
             (size_t(k.bits[2]) * 83492791u);
    }
  };
  MeshData& m_mesh;
  std::unordered_map<Key, uint32_t, Hash> m_index;
};

void add_triangle(MeshData& m, Welder& weld, const glm::vec3 (&corner)[3], size_t n) {
  const uint32_t v[3] = {weld.vertex(corner[0]), weld.vertex(corner[1]), weld.vertex(corner[2])};
  m.add_polygon(v, 3, m.positions.size(), [n] { return "triangle " + std::to_string(n + 1); });
}

MeshData read_binary(std::string_view bytes, uint32_t count) {
  MeshData m;
  Welder weld(m);
  for (size_t t = 0; t < count; ++t) {
    const char* p = bytes.data() + 84 + 50 * t + 12;  // after the facet normal
    glm::vec3 corner[3];
    std::memcpy(corner, p, sizeof corner);
    add_triangle(m, weld, corner, t);
  }
  return m;
}

MeshData read_ascii(std::string_view text, const std::string& path) {
  TextScan scan(text, path);
  MeshData m;
  Welder weld(m);
  glm::vec3 corner[3];
  size_t corners = 0, triangles = 0;
  bool ended = false;
  for (std::string_view w; scan.word(w) && !ended;) {
    if (w == "vertex") {
      if (corners == 3) scan.fail("a facet has more than three vertices");
      corner[corners].x = float(scan.number());
      corner[corners].y = float(scan.number());
      corner[corners++].z = float(scan.number());
    } else if (w == "endloop") {
      if (corners != 3) scan.fail("a facet has " + std::to_string(corners) + " vertices, not 3");
      add_triangle(m, weld, corner, triangles++);
      corners = 0;
    } else if (w == "endsolid") {
      ended = true;
    }
  }
  if (!ended) throw InputError(path, "the ASCII STL file ends without 'endsolid' (cut short?)");
  return m;
}

}  // namespace

MeshData read_stl(std::string_view bytes, const std::string& path) {
  uint32_t count = 0;
  if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);
  if (bytes.size() >= 84 && bytes.size() == 84 + 50 * uint64_t(count))
    return read_binary(bytes, count);
  if (bytes.substr(0, 5) == "solid") return read_ascii(bytes, path);
  if (bytes.size() < 84) throw InputError(path, "not an STL file (too short, and no 'solid')");
  throw InputError(path, "not an STL file: binary STL with " + std::to_string(count) +
                             " triangles is " + std::to_string(84 + 50 * uint64_t(count)) +
                             " bytes, the file is " + std::to_string(bytes.size()) +
                             ", and it does not start with 'solid'");
}

}  // namespace sylva
