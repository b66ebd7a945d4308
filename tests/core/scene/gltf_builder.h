// Small glTF files for the tests of instancing and cameras: a JSON document and its buffer
// (embedded as a data URI), with meshes, nodes, raw accessors (for EXT_mesh_gpu_instancing
// attributes of any type) and cameras added one by one.
#pragma once

#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sylva::test {

class GltfBuilder {
 public:
  using Json = nlohmann::json;

  GltfBuilder() {
    m_json = Json::parse(R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}],
                            "nodes": [], "meshes": [], "accessors": [], "bufferViews": []})");
  }

  // An accessor over `bytes` of raw data; returns its index.
  int accessor(const void* data, size_t bytes, int component_type, size_t count, const char* type,
               bool normalized = false) {
    while (m_bin.size() % 4)
      m_bin.push_back('\0');
    const size_t offset = m_bin.size();
    m_bin.append(static_cast<const char*>(data), bytes);
    m_json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    Json a = {{"bufferView", m_json["bufferViews"].size() - 1},
              {"componentType", component_type},
              {"count", count},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    m_json["accessors"].push_back(a);
    return int(m_json["accessors"].size() - 1);
  }
  int floats(const std::vector<float>& v, const char* type, size_t per) {
    return accessor(v.data(), v.size() * 4, 5126, v.size() / per, type);
  }

  // A flat grid of cols x rows quads (2 triangles each) in the XY plane, 1 unit across,
  // lower-left corner at `corner`, named `name`; returns the mesh index.
  int grid_mesh(const std::string& name, int cols, int rows, float corner_x = 0.0f,
                float corner_y = 0.0f) {
    std::vector<float> p;
    std::vector<uint16_t> idx;
    for (int y = 0; y <= rows; ++y)
      for (int x = 0; x <= cols; ++x)
        p.insert(p.end(),
                 {corner_x + float(x) / float(cols), corner_y + float(y) / float(rows), 0.0f});
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        const auto a = uint16_t(y * (cols + 1) + x), b = uint16_t(a + 1),
                   c = uint16_t(a + cols + 1), d = uint16_t(c + 1);
        idx.insert(idx.end(), {a, b, d, a, d, c});
      }
    const int pos = floats(p, "VEC3", 3);
    m_json["accessors"][size_t(pos)]["min"] = {corner_x, corner_y, 0.0f};
    m_json["accessors"][size_t(pos)]["max"] = {corner_x + 1.0f, corner_y + 1.0f, 0.0f};
    const int ind = accessor(idx.data(), idx.size() * 2, 5123, idx.size(), "SCALAR");
    m_json["meshes"].push_back(
        {{"name", name},
         {"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", ind}}}}});
    return int(m_json["meshes"].size() - 1);
  }

  // A node (a root unless `parent` >= 0); `extra` is merged into the node's JSON.
  int node(const Json& extra, int parent = -1) {
    Json n = extra.is_null() ? Json::object() : extra;
    m_json["nodes"].push_back(n);
    const int i = int(m_json["nodes"].size() - 1);
    if (parent < 0)
      m_json["scenes"][0]["nodes"].push_back(i);
    else
      m_json["nodes"][size_t(parent)]["children"].push_back(i);
    return i;
  }

  Json& json() { return m_json; }

  // The finished document with its buffer embedded.
  std::string text() const {
    Json j = m_json;
    std::string bin = m_bin;
    while (bin.size() % 4)
      bin.push_back('\0');
    j["buffers"] = {{{"byteLength", bin.size()},
                     {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    if (j["accessors"].empty()) j.erase("accessors");
    if (j["bufferViews"].empty()) j.erase("bufferViews");
    return j.dump();
  }

 private:
  static std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
      uint32_t v = uint32_t(uint8_t(in[i])) << 16;
      if (i + 1 < in.size()) v |= uint32_t(uint8_t(in[i + 1])) << 8;
      if (i + 2 < in.size()) v |= uint8_t(in[i + 2]);
      out += k[(v >> 18) & 63];
      out += k[(v >> 12) & 63];
      out += i + 1 < in.size() ? k[(v >> 6) & 63] : '=';
      out += i + 2 < in.size() ? k[v & 63] : '=';
    }
    return out;
  }

  Json m_json;
  std::string m_bin;
};

}  // namespace sylva::test
