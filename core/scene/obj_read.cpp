// Wavefront OBJ, read strictly: `v x y z [w]` or `v x y z r g b`, `vt u [v [w]]`, `vn x y z`
// and `f` with corners `v`, `v/vt`, `v//vn` or `v/vt/vn`; every other statement (o, g, s,
// usemtl, mtllib, l, p, curves, unknown keywords) is ignored, and `mtllib` is not followed.
// '#' starts a comment; a UTF-8 byte order mark is skipped. Each number must be a decimal
// number a float holds finitely, with nothing after it; each index a whole number (unsigned or
// with a '-', no point), 1-based or negative counting back from the last element declared, and
// naming an element declared before its line. Anything else is InputError(path, "line N:
// expected ..., got '<token>'").
//
// Sylva's own reader rather than a strict pre-pass in front of tinyobjloader: a pre-pass
// checks the text by one set of rules and tinyobjloader then converts it by its own (indices
// through int, wrapping modulo 2^32; words that are not numbers read as 0; its own float
// parser and colour detection), so the two would have to agree on every token for the mesh
// to be what the text says, and each disagreement is a silent misreading again. One parser
// reads each token once, through TextScan, with the PLY and OFF readers' words and errors.
//
// OBJ indexes positions, texture coordinates and normals separately; Sylva keeps one vertex
// per position and takes its uv and normal from the first face corner that names one, so that
// leaves stay connected across uv seams. `w` is read and not used (it weights rational
// curves); colours are kept when every vertex has one. Faces of more than three corners are
// fans around their first corner (mesh_data.h).
#include <algorithm>

#include "core/scene/mesh_formats.h"
#include "core/scene/text_scan.h"

namespace sylva {
namespace {

// What an index names: "vertex" and its keyword "v", ...
struct Element {
  const char* name;
  const char* keyword;
};
constexpr Element kVertex{"vertex", "v"}, kUv{"texture coordinate", "vt"}, kNormal{"normal", "vn"};

// The line as an error shows it.
std::string line_text(const std::vector<std::string_view>& w) {
  std::string s(w[0]);
  for (size_t k = 1; k < w.size(); ++k)
    s.append(" ").append(w[k]);
  return TextScan::quote(s);
}

// A NUL byte anywhere is an error naming the word it is in: OBJ is text, and a NUL in it
// marks a binary or damaged file.
void refuse_nul(std::string_view text, const std::string& path) {
  const size_t at = text.find('\0');
  if (at == std::string_view::npos) return;
  const auto blank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
  };
  size_t begin = at, end = at;
  while (begin > 0 && !blank(text[begin - 1]))
    --begin;
  while (end < text.size() && !blank(text[end]))
    ++end;
  const size_t line = 1 + size_t(std::count(text.begin(), text.begin() + at, '\n'));
  throw InputError(path, "line " + std::to_string(line) + ": expected text, got a NUL byte in " +
                             TextScan::quote(text.substr(begin, end - begin)));
}

class ObjReader {
 public:
  ObjReader(std::string_view text, const std::string& path) : m_scan(text, path, '#') {}

  MeshData read() {
    for (std::vector<std::string_view> w; m_scan.line(w);) {
      if (w[0] == "v")
        vertex(w);
      else if (w[0] == "vt")
        uv(w);
      else if (w[0] == "vn")
        normal(w);
      else if (w[0] == "f")
        face(w);
    }
    const size_t n = m_mesh.positions.size();
    if (m_colored != n) m_mesh.colors.clear();
    if (!m_mesh.uvs.empty()) m_mesh.uvs.resize(n, glm::vec2(0.0f));
    if (!m_mesh.normals.empty()) m_mesh.normals.resize(n, glm::vec3(0.0f));
    return std::move(m_mesh);
  }

 private:
  struct Corner {  // indices into positions, m_uvs and m_normals (-1: none)
    uint32_t v = 0;
    int64_t t = -1, n = -1;
  };

  void vertex(const std::vector<std::string_view>& w) {
    if (w.size() != 4 && w.size() != 5 && w.size() != 7)
      m_scan.fail("expected 'v x y z', 'v x y z w' or 'v x y z r g b', got " + line_text(w));
    if (m_mesh.positions.size() == UINT32_MAX)
      m_scan.fail("more vertices than 32-bit indices hold");
    float v[6] = {0, 0, 0, 0, 0, 0};
    for (size_t k = 1; k < w.size(); ++k)
      v[k - 1] = m_scan.finite_float(w[k]);
    m_mesh.positions.emplace_back(v[0], v[1], v[2]);
    if (w.size() == 7) {
      for (int k = 3; k < 6; ++k)
        v[k] = unit_channel(v[k], m_scan.path(), m_scan.where());
      ++m_colored;
    }
    m_mesh.colors.emplace_back(v[3], v[4], v[5], 1.0f);  // kept if every vertex has one
  }

  void uv(const std::vector<std::string_view>& w) {
    if (w.size() < 2 || w.size() > 4)
      m_scan.fail("expected 'vt u', 'vt u v' or 'vt u v w', got " + line_text(w));
    m_uvs.emplace_back(m_scan.finite_float(w[1]), w.size() > 2 ? m_scan.finite_float(w[2]) : 0.0f);
    if (w.size() > 3) m_scan.finite_float(w[3]);
  }

  void normal(const std::vector<std::string_view>& w) {
    if (w.size() != 4) m_scan.fail("expected 'vn x y z', got " + line_text(w));
    m_normals.emplace_back(m_scan.finite_float(w[1]), m_scan.finite_float(w[2]),
                           m_scan.finite_float(w[3]));
  }

  // Index `w` of `corner` into the `declared` elements of kind `e`, 0-based.
  uint32_t index(std::string_view w, std::string_view corner, size_t declared,
                 const Element& e) const {
    const bool negative = !w.empty() && w[0] == '-';
    bool ok = w.size() > (negative ? 1u : 0u);
    uint64_t v = 0;
    for (size_t k = negative ? 1 : 0; k < w.size() && ok; ++k) {
      ok = w[k] >= '0' && w[k] <= '9';
      v = std::min<uint64_t>(v * 10 + uint64_t(w[k] - '0'), uint64_t(1) << 40);  // no wrap
    }
    if (ok && v >= 1 && v <= declared) return uint32_t(negative ? declared - v : v - 1);
    const std::string in = corner.size() > w.size() ? " in " + TextScan::quote(corner) : "";
    const std::string n = std::to_string(declared), got = ", got " + TextScan::quote(w) + in;
    if (declared == 0)
      m_scan.fail(std::string("expected a ") + e.name + " index of a '" + e.keyword +
                  "' line before this one (there is none)" + got);
    m_scan.fail(std::string("expected a ") + e.name + " index (1 to " + n + ", or -1 to -" + n +
                " counting back from the last '" + e.keyword + "')" + got);
  }

  void face(const std::vector<std::string_view>& w) {
    if (w.size() < 4)
      m_scan.fail("expected a face of at least 3 corners, got " + std::to_string(w.size() - 1) +
                  " in " + line_text(w));
    m_loop.clear();
    m_corners.clear();
    for (size_t k = 1; k < w.size(); ++k) {
      const std::string_view c = w[k];
      const size_t a = c.find('/'), b = a == c.npos ? c.npos : c.find('/', a + 1);
      if (b != c.npos && c.find('/', b + 1) != c.npos)
        m_scan.fail("expected a face corner 'v', 'v/vt', 'v//vn' or 'v/vt/vn', got " +
                    TextScan::quote(c));
      const std::string_view pv = c.substr(0, a);
      const std::string_view pt = a == c.npos ? "" : c.substr(a + 1, b - a - 1);
      const std::string_view pn = b == c.npos ? "" : c.substr(b + 1);
      Corner corner;
      corner.v = index(pv, c, m_mesh.positions.size(), kVertex);
      // "1/" and "1//" name nothing after a slash: an error, not a silent default.
      if (a != c.npos && (b == c.npos || !pt.empty())) corner.t = index(pt, c, m_uvs.size(), kUv);
      if (b != c.npos) corner.n = index(pn, c, m_normals.size(), kNormal);
      m_loop.push_back(corner.v);
      m_corners.push_back(corner);
    }
    m_mesh.add_polygon(m_loop.data(), m_loop.size(), m_mesh.positions.size(),
                       [this] { return m_scan.where(); });
    for (const Corner& k : m_corners)
      take_corner(k);
  }

  // Gives a vertex the uv and normal of the first corner that names one.
  void take_corner(const Corner& k) {
    const size_t n = m_mesh.positions.size();
    if (k.t >= 0) {
      if (m_mesh.uvs.size() < n) m_mesh.uvs.resize(n), m_has_uv.resize(n);
      if (!m_has_uv[k.v]) m_mesh.uvs[k.v] = m_uvs[size_t(k.t)], m_has_uv[k.v] = true;
    }
    if (k.n >= 0) {
      if (m_mesh.normals.size() < n) m_mesh.normals.resize(n), m_has_normal.resize(n);
      if (!m_has_normal[k.v])
        m_mesh.normals[k.v] = m_normals[size_t(k.n)], m_has_normal[k.v] = true;
    }
  }

  TextScan m_scan;
  MeshData m_mesh;
  size_t m_colored = 0;                      // vertices with a colour
  std::vector<glm::vec2> m_uvs;              // the `vt` lines so far
  std::vector<glm::vec3> m_normals;          // the `vn` lines so far
  std::vector<bool> m_has_uv, m_has_normal;  // per position: taken from a corner
  std::vector<uint32_t> m_loop;
  std::vector<Corner> m_corners;
};

}  // namespace

MeshData read_obj(std::string_view text, const std::string& path) {
  refuse_nul(text, path);
  // A UTF-8 byte order mark (Windows tools write one) would hide the first line's keyword,
  // and a `v` line lost so would shift every index after it.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return ObjReader(text, path).read();
}

}  // namespace sylva
