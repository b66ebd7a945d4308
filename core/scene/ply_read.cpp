// Stanford PLY data after the header (ply_header.h): the vertex element's x y z, normals,
// texture coordinates and colours; the face element's vertex_indices (or vertex_index) list;
// every other element and property is read past. ASCII values are whitespace-separated;
// binary values are packed in the header's byte order.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/scene/mesh_formats.h"
#include "core/scene/ply_header.h"
#include "core/scene/text_scan.h"

namespace sylva {
namespace {

// The data's values one at a time, ASCII or binary; the end of the data is an error.
class PlyValues {
 public:
  PlyValues(std::string_view bytes, const PlyHeader& h, const std::string& path)
      : m_scan(bytes.substr(h.data_offset), path, 0,
               1 + size_t(std::count(bytes.begin(), bytes.begin() + h.data_offset, '\n'))),
        m_bytes(bytes),
        m_pos(h.data_offset),
        m_format(h.format),
        m_path(path) {}

  double next(PlyType t) {
    if (m_format == PlyHeader::Format::Ascii) return m_scan.number();
    const size_t n = ply_size(t);
    if (m_bytes.size() - m_pos < n) throw InputError(m_path, where() + ": the file ends here");
    unsigned char b[8];
    std::memcpy(b, m_bytes.data() + m_pos, n);
    m_pos += n;
    if (m_format == PlyHeader::Format::BigEndian) std::reverse(b, b + n);
    return decode(t, b);
  }
  // A list's length: a whole number no larger than the values left could hold.
  size_t length(PlyType t) {
    const double v = next(t);
    if (!(v >= 0.0 && v <= double(m_bytes.size())) || std::floor(v) != v)
      throw InputError(m_path, where() + ": a list length of " + std::to_string(v));
    return size_t(v);
  }
  const std::string& path() const { return m_path; }
  void at(const std::string& element, uint64_t item) {
    m_element = element;
    m_item = item;
  }
  std::string where() const {
    const std::string place = "element '" + m_element + "' item " + std::to_string(m_item + 1);
    return m_format == PlyHeader::Format::Ascii ? m_scan.where() + " (" + place + ")" : place;
  }

 private:
  static double decode(PlyType t, const unsigned char* b) {
    switch (t) {
      case PlyType::Int8:
        return double(int8_t(b[0]));
      case PlyType::Uint8:
        return double(b[0]);
      case PlyType::Int16:
        return typed<int16_t>(b);
      case PlyType::Uint16:
        return typed<uint16_t>(b);
      case PlyType::Int32:
        return typed<int32_t>(b);
      case PlyType::Uint32:
        return typed<uint32_t>(b);
      case PlyType::Float32:
        return typed<float>(b);
      case PlyType::Float64:
        return typed<double>(b);
    }
    return 0.0;
  }
  template <class T>
  static double typed(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return double(v);
  }
  TextScan m_scan;
  std::string_view m_bytes;
  size_t m_pos;
  PlyHeader::Format m_format;
  const std::string& m_path;
  std::string m_element;
  uint64_t m_item = 0;
};

// Where each vertex property goes: 0-2 position, 3-5 normal, 6-7 uv, 8-11 colour, -1 nowhere.
int vertex_slot(const std::string& name) {
  static const char* kNames[][3] = {{"x", "", ""},
                                    {"y", "", ""},
                                    {"z", "", ""},
                                    {"nx", "", ""},
                                    {"ny", "", ""},
                                    {"nz", "", ""},
                                    {"u", "s", "texture_u"},
                                    {"v", "t", "texture_v"},
                                    {"red", "r", "diffuse_red"},
                                    {"green", "g", "diffuse_green"},
                                    {"blue", "b", "diffuse_blue"},
                                    {"alpha", "a", ""}};
  for (int s = 0; s < 12; ++s)
    for (const char* n : kNames[s])
      if (*n && name == n) return s;
  return -1;
}

void skip_item(PlyValues& in, const PlyProperty& p) {
  if (!p.list) {
    in.next(p.type);
    return;
  }
  for (size_t k = in.length(p.count_type); k > 0; --k)
    in.next(p.type);
}

void read_vertices(PlyValues& in, const PlyElement& e, MeshData& m) {
  std::vector<int> slot;
  bool has[12] = {};
  for (const PlyProperty& p : e.properties) {
    slot.push_back(p.list ? -1 : vertex_slot(p.name));
    if (slot.back() >= 0) has[slot.back()] = true;
  }
  if (!has[0] || !has[1] || !has[2])
    throw InputError(in.path(), "the vertex element has no x, y and z properties");
  const bool normals = has[3] && has[4] && has[5], uvs = has[6] && has[7];
  const bool colors = has[8] && has[9] && has[10];
  for (uint64_t i = 0; i < e.count; ++i) {
    in.at(e.name, i);
    double v[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    for (size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (slot[k] < 0)
        skip_item(in, p);
      else
        v[slot[k]] = in.next(p.type) / (slot[k] >= 8 ? ply_max(p.type) : 1.0);
    }
    m.positions.emplace_back(v[0], v[1], v[2]);
    if (normals) m.normals.emplace_back(v[3], v[4], v[5]);
    if (uvs) m.uvs.emplace_back(v[6], v[7]);
    if (colors) {
      glm::vec4 c;
      for (int k = 0; k < 4; ++k)
        c[k] = unit_channel(v[8 + k], in.path(), in.where());
      m.colors.push_back(c);
    }
  }
}

void read_faces(PlyValues& in, const PlyElement& e, size_t vertex_count, MeshData& m) {
  std::vector<uint32_t> loop;
  for (uint64_t i = 0; i < e.count; ++i) {
    in.at(e.name, i);
    for (const PlyProperty& p : e.properties) {
      if (!p.list || (p.name != "vertex_indices" && p.name != "vertex_index")) {
        skip_item(in, p);
        continue;
      }
      loop.clear();
      for (size_t k = in.length(p.count_type); k > 0; --k) {
        const double v = in.next(p.type);
        loop.push_back(v >= 0.0 && v < 4294967295.0 && std::floor(v) == v ? uint32_t(v)
                                                                          : UINT32_MAX);
      }
      m.add_polygon(loop.data(), loop.size(), vertex_count, [&in] { return in.where(); });
    }
  }
}

}  // namespace

MeshData read_ply(std::string_view bytes, const std::string& path) {
  const PlyHeader h = read_ply_header(bytes, path);
  const PlyElement* vertices = h.find("vertex");
  if (!vertices) throw InputError(path, "the PLY file has no vertex element");
  MeshData m;
  PlyValues in(bytes, h, path);
  for (const PlyElement& e : h.elements) {
    in.at(e.name, 0);
    if (&e == vertices)
      read_vertices(in, e, m);
    else if (e.name == "face")
      read_faces(in, e, size_t(vertices->count), m);
    else
      for (uint64_t i = 0; i < e.count; ++i) {
        in.at(e.name, i);
        for (const PlyProperty& p : e.properties)
          skip_item(in, p);
      }
  }
  return m;
}

}  // namespace sylva
