// Guarding OpenMesh's readers against hostile files (found by tests/fuzz/): OpenMesh 9's
// readers write attributes through vertex, face and halfedge handles they never checked (an
// OBJ face whose vertex index is out of range writes its texture coordinate past the end),
// cast out-of-range float colours to bytes (undefined behaviour), reserve whatever counts a
// header claims, and loop forever on some malformed PLY headers. SafeImporter drops writes
// through handles out of range, clamps colours to [0, 1] first and caps reservations by the
// file's size; check_ply_header refuses a PLY header line that is not in the format before
// OpenMesh reads it. Header-only (templates on the mesh type); used by mesh_read.cpp.
#pragma once

#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {

template <class Mesh>
class SafeImporter : public OpenMesh::IO::ImporterT<Mesh> {
  using Base = OpenMesh::IO::ImporterT<Mesh>;
  using VH = OpenMesh::VertexHandle;
  using FH = OpenMesh::FaceHandle;
  using HH = OpenMesh::HalfedgeHandle;

 public:
  SafeImporter(Mesh& mesh, size_t file_bytes) : Base(mesh), m_mesh(mesh), m_bytes(file_bytes) {}

  void set_point(VH v, const OpenMesh::Vec3f& p) override {
    if (ok(v)) Base::set_point(v, p);
  }
  void set_normal(VH v, const OpenMesh::Vec3f& n) override {
    if (ok(v)) Base::set_normal(v, n);
  }
  void set_normal(VH v, const OpenMesh::Vec3d& n) override {
    if (ok(v)) Base::set_normal(v, n);
  }
  void set_color(VH v, const OpenMesh::Vec3uc& c) override {
    if (ok(v)) Base::set_color(v, c);
  }
  void set_color(VH v, const OpenMesh::Vec4uc& c) override {
    if (ok(v)) Base::set_color(v, c);
  }
  void set_color(VH v, const OpenMesh::Vec3f& c) override {
    if (ok(v)) Base::set_color(v, unit(c));
  }
  void set_color(VH v, const OpenMesh::Vec4f& c) override {
    if (ok(v)) Base::set_color(v, unit(c));
  }
  void set_texcoord(VH v, const OpenMesh::Vec2f& t) override {
    if (ok(v)) Base::set_texcoord(v, t);
  }
  void set_texcoord(VH v, const OpenMesh::Vec3f& t) override {
    if (ok(v)) Base::set_texcoord(v, t);
  }
  void set_texcoord(HH h, const OpenMesh::Vec2f& t) override {
    if (ok(h)) Base::set_texcoord(h, t);
  }
  void set_texcoord(HH h, const OpenMesh::Vec3f& t) override {
    if (ok(h)) Base::set_texcoord(h, t);
  }
  void set_normal(FH f, const OpenMesh::Vec3f& n) override {
    if (ok(f)) Base::set_normal(f, n);
  }
  void set_normal(FH f, const OpenMesh::Vec3d& n) override {
    if (ok(f)) Base::set_normal(f, n);
  }
  void set_color(FH f, const OpenMesh::Vec3uc& c) override {
    if (ok(f)) Base::set_color(f, c);
  }
  void set_color(FH f, const OpenMesh::Vec4uc& c) override {
    if (ok(f)) Base::set_color(f, c);
  }
  void set_color(FH f, const OpenMesh::Vec3f& c) override {
    if (ok(f)) Base::set_color(f, unit(c));
  }
  void set_color(FH f, const OpenMesh::Vec4f& c) override {
    if (ok(f)) Base::set_color(f, unit(c));
  }
  void set_face_texindex(FH f, int id) override {
    if (ok(f)) Base::set_face_texindex(f, id);
  }
  void add_face_texcoords(FH f, VH v, const std::vector<OpenMesh::Vec2f>& t) override {
    if (ok(f) && ok(v)) Base::add_face_texcoords(f, v, t);
  }
  void add_face_texcoords(FH f, VH v, const std::vector<OpenMesh::Vec3f>& t) override {
    if (ok(f) && ok(v)) Base::add_face_texcoords(f, v, t);
  }
  // Every element takes at least a byte of the file: no more is reserved.
  void reserve(unsigned int v, unsigned int e, unsigned int f) override {
    const auto cap = [this](unsigned int n) { return unsigned(std::min<size_t>(n, m_bytes)); };
    Base::reserve(cap(v), cap(e), cap(f));
  }
  using Base::set_color;
  using Base::set_normal;
  using Base::set_status;
  using Base::set_texcoord;

 private:
  bool ok(VH v) const { return v.idx() >= 0 && size_t(v.idx()) < m_mesh.n_vertices(); }
  bool ok(FH f) const { return f.idx() >= 0 && size_t(f.idx()) < m_mesh.n_faces(); }
  bool ok(HH h) const { return h.idx() >= 0 && size_t(h.idx()) < m_mesh.n_halfedges(); }
  template <class V>
  static V unit(V c) {
    for (auto& x : c)
      x = std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : 0.0f;
    return c;
  }
  Mesh& m_mesh;
  size_t m_bytes;
};

// Throws InputError(path, ...) unless every line of the PLY header between "ply" and
// "end_header" is a format, comment, obj_info, element or property line of the PLY format.
inline void check_ply_header(const std::string& path) {
  static const char* kTypes[] = {"char",  "uchar",  "short",   "ushort", "int",   "uint",
                                 "float", "double", "int8",    "uint8",  "int16", "uint16",
                                 "int32", "uint32", "float32", "float64"};
  const auto type = [](const std::string& t) {
    return std::find(std::begin(kTypes), std::end(kTypes), t) != std::end(kTypes);
  };
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (int n = 1; std::getline(in, line) && n <= 10000; ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "end_header") return;
    std::istringstream in_line(line);
    std::vector<std::string> w;
    for (std::string word; in_line >> word;)
      w.push_back(word);
    const auto is = [&w](size_t k, const char* text) { return w.size() > k && w[k] == text; };
    const bool count = w.size() == 3 && w[2].find_first_not_of("0123456789") == std::string::npos;
    const bool good =
        (n == 1 && line == "ply") || w.empty() || is(0, "comment") || is(0, "obj_info") ||
        (is(0, "format") && w.size() == 3) || (is(0, "element") && count) ||
        (is(0, "property") && w.size() == 3 && type(w[1])) ||
        (is(0, "property") && is(1, "list") && w.size() == 5 && type(w[2]) && type(w[3]));
    if (!good)
      throw InputError(path, "not a PLY header line (line " + std::to_string(n) + "): '" +
                                 line.substr(0, 80) + "'");
  }
  throw InputError(path, "the PLY header has no end_header line");
}

}  // namespace sylva
