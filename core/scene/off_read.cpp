// Object File Format (Geomview's OFF), ASCII: an optional [ST][C][N]OFF keyword, the counts
// "vertices faces edges", one vertex per line (x y z [nx ny nz] [r g b [a]] [s t]) and one face
// per line (n i1 ... in [colour]). '#' starts a comment.
#include <cmath>

#include "core/scene/mesh_formats.h"
#include "core/scene/text_scan.h"

namespace sylva {
namespace {

struct OffLayout {
  bool normals = false, colors = false, uvs = false;
};

// Reads the keyword, if any; returns the words after it on its line (maybe the counts).
std::vector<std::string_view> header(TextScan& scan, OffLayout& layout) {
  std::vector<std::string_view> w;
  if (!scan.line(w)) scan.fail("the file has no OFF header");
  std::string_view key = w[0];
  if (key.size() < 3 || key.substr(key.size() - 3) != "OFF") return w;  // counts, no keyword
  key.remove_suffix(3);
  if (key.substr(0, 2) == "ST") layout.uvs = true, key.remove_prefix(2);
  if (!key.empty() && key[0] == 'C') layout.colors = true, key.remove_prefix(1);
  if (!key.empty() && key[0] == 'N') layout.normals = true, key.remove_prefix(1);
  if (!key.empty())
    scan.fail(TextScan::quote(w[0]) + " OFF files (4D, nD) are not supported, only 3D");
  if (w.size() > 1 && w[1] == "BINARY") scan.fail("binary OFF files are not supported");
  w.erase(w.begin());
  if (w.empty() && !scan.line(w)) scan.fail("the file ends before the vertex and face counts");
  return w;
}

glm::vec4 vertex_color(const TextScan& scan, const std::vector<std::string_view>& w, size_t at,
                       size_t n) {
  double c[4] = {0, 0, 0, 1};
  bool whole = true, over_one = false;
  for (size_t k = 0; k < n; ++k) {
    c[k] = scan.number(w[at + k]);
    whole = whole && std::floor(c[k]) == c[k];
    over_one = over_one || c[k] > 1.0;
  }
  const double scale = whole && over_one ? 1.0 / 255.0 : 1.0;  // 0-255 integers, or 0-1
  glm::vec4 out;
  for (int k = 0; k < 4; ++k)
    out[k] = unit_channel(k < int(n) ? c[k] * scale : c[k], scan.path(), scan.where());
  return out;
}

void read_vertex(TextScan& scan, const OffLayout& layout, MeshData& m) {
  std::vector<std::string_view> w;
  if (!scan.line(w)) scan.fail("the file ends before all its vertices");
  const size_t need = 3 + (layout.normals ? 3 : 0) + (layout.uvs ? 2 : 0);
  const size_t colors = w.size() >= need ? w.size() - need : 0;
  if (w.size() < need || (layout.colors ? colors < 3 || colors > 4 : colors != 0))
    scan.fail("a vertex line has " + std::to_string(w.size()) + " numbers, expected " +
              std::to_string(need) + (layout.colors ? " plus a 3- or 4-number colour" : ""));
  m.positions.emplace_back(scan.number(w[0]), scan.number(w[1]), scan.number(w[2]));
  size_t at = 3;
  if (layout.normals) {
    m.normals.emplace_back(scan.number(w[3]), scan.number(w[4]), scan.number(w[5]));
    at = 6;
  }
  if (layout.colors) m.colors.push_back(vertex_color(scan, w, at, colors));
  at += colors;
  if (layout.uvs) m.uvs.emplace_back(scan.number(w[at]), scan.number(w[at + 1]));
}

void read_face(TextScan& scan, size_t vertex_count, MeshData& m, std::vector<uint32_t>& loop) {
  std::vector<std::string_view> w;
  if (!scan.line(w)) scan.fail("the file ends before all its faces");
  const uint64_t n = scan.count(w[0], "a face's vertex count", w.size() - 1);
  loop.clear();
  for (size_t k = 1; k <= n; ++k)
    loop.push_back(uint32_t(scan.count(w[k], "a vertex index", UINT32_MAX)));
  m.add_polygon(loop.data(), loop.size(), vertex_count, [&scan] { return scan.where(); });
}

}  // namespace

MeshData read_off(std::string_view text, const std::string& path) {
  TextScan scan(text, path, '#');
  OffLayout layout;
  const std::vector<std::string_view> counts = header(scan, layout);
  if (counts.size() < 2 || counts.size() > 3)
    scan.fail("expected the counts 'vertices faces edges'");
  const uint64_t nv = scan.count(counts[0], "the vertex count", UINT32_MAX);
  const uint64_t nf = scan.count(counts[1], "the face count", UINT32_MAX);
  MeshData m;
  for (uint64_t i = 0; i < nv; ++i)
    read_vertex(scan, layout, m);
  std::vector<uint32_t> loop;
  for (uint64_t i = 0; i < nf; ++i)
    read_face(scan, size_t(nv), m, loop);
  return m;
}

}  // namespace sylva
