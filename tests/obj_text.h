// A mesh as Wavefront OBJ text, for the tests and the fuzz harnesses' round trips (Sylva writes
// no OBJ files itself): `v x y z [r g b]` per position, `vt` and `vn` per position when the
// mesh has them, and one `f a/a/a b/b/b c/c/c` per triangle. Floats are printed with 9
// significant digits, which reads back as the same float; colours lose their alpha (OBJ has
// none).
#pragma once

#include <cstdio>
#include <glm/glm.hpp>
#include <string>

namespace sylva::test {

inline void append_floats(std::string& s, const char* keyword, const float* v, int n) {
  s += keyword;
  char buf[32];
  for (int k = 0; k < n; ++k) {
    std::snprintf(buf, sizeof buf, " %.9g", double(v[k]));
    s += buf;
  }
  s += '\n';
}

// `M` is a Mesh or a MeshData (positions, normals, uvs, colors, indices).
template <class M>
std::string obj_text(const M& m) {
  std::string s = "# written by the Sylva tests\no mesh\n";
  const bool colors = !m.colors.empty(), uvs = !m.uvs.empty(), normals = !m.normals.empty();
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const float v[6] = {m.positions[i].x,
                        m.positions[i].y,
                        m.positions[i].z,
                        colors ? m.colors[i].r : 0.0f,
                        colors ? m.colors[i].g : 0.0f,
                        colors ? m.colors[i].b : 0.0f};
    append_floats(s, "v", v, colors ? 6 : 3);
  }
  for (size_t i = 0; uvs && i < m.uvs.size(); ++i)
    append_floats(s, "vt", &m.uvs[i].x, 2);
  for (size_t i = 0; normals && i < m.normals.size(); ++i)
    append_floats(s, "vn", &m.normals[i].x, 3);
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    s += 'f';
    for (size_t k = 0; k < 3; ++k) {
      const std::string i = std::to_string(m.indices[t + k] + 1);
      s += ' ' + i + (uvs || normals ? "/" : "") + (uvs ? i : "") + (normals ? "/" + i : "");
    }
    s += '\n';
  }
  return s;
}

}  // namespace sylva::test
