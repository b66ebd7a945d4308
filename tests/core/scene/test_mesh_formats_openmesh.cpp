// Sylva's mesh readers against files another implementation wrote: the shared fern's first
// mesh through OpenMesh's writers (OBJ with normals and uvs, OFF with colours, PLY in ASCII and
// both binary byte orders, STL in ASCII and binary) reads back as the same triangles, positions,
// normals, uvs and colours.
// OpenMesh's default-constructed colour vectors trip GCC 12's -Wmaybe-uninitialized inside the
// standard library, reported at the library's location: silenced before any header is seen.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <gtest/gtest.h>

#include <filesystem>

#include "core/scene/load.h"
#include "tests/openmesh_copy.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

using O = OpenMesh::IO::Options;
using test::openmesh_color;

glm::vec3 rgb(const OpenMesh::Vec3uc& c) {
  return glm::vec3(c[0], c[1], c[2]) / 255.0f;
}

struct Kind {
  const char* name;
  O::Flag flags;
  bool normals, uvs, colors, welded;
};

void expect_same(const Mesh& want, const Mesh& got, const Kind& k) {
  ASSERT_EQ(got.triangle_count(), want.triangle_count()) << k.name;
  if (k.welded) return;  // STL: compared by bounds below
  ASSERT_EQ(got.positions.size(), want.positions.size()) << k.name;
  EXPECT_EQ(got.indices, want.indices) << k.name;
  for (size_t v = 0; v < want.positions.size(); ++v) {
    ASSERT_NEAR(glm::distance(got.positions[v], want.positions[v]), 0.0f, 1e-5f) << k.name << v;
    if (k.normals) {
      ASSERT_NEAR(glm::dot(got.normals[v], glm::normalize(want.normals[v])), 1.0f, 1e-4f)
          << k.name << v;
    }
    if (k.uvs) {
      ASSERT_NEAR(glm::distance(got.uvs[v], want.uvs[v]), 0.0f, 1e-5f) << k.name << v;
    }
    if (k.colors) {
      ASSERT_NEAR(glm::distance(glm::vec3(got.colors[v]), rgb(openmesh_color(v))), 0.0f, 1e-6f)
          << k.name << v;
    }
  }
}

TEST(MeshFormats, FilesOpenMeshWroteReadBackTheSame) {
  const Scene fern = load_scene(test::fern_path());
  const Mesh& want = fern.meshes.at(0);
  ASSERT_EQ(want.uvs.size(), want.positions.size());
  const test::TriMesh tm = test::openmesh_copy(want);
  Bounds bounds;
  for (const glm::vec3& p : want.positions)
    bounds.extend(p);
  const Kind kinds[] = {
      {"fern.obj", O::Flag(O::VertexNormal | O::VertexTexCoord), true, true, false, false},
      {"fern.off", O::Flag(O::VertexColor), false, false, true, false},
      {"fern.ply", O::Flag(O::VertexNormal | O::VertexColor), true, false, true, false},
      {"fern_lsb.ply", O::Flag(O::Binary | O::LSB | O::VertexNormal | O::VertexColor), true, false,
       true, false},
      {"fern_msb.ply", O::Flag(O::Binary | O::MSB | O::VertexNormal | O::VertexColor), true, false,
       true, false},
      {"fern.stl", O::Flag(O::Default), false, false, false, true},
      {"fern_bin.stl", O::Flag(O::Binary), false, false, false, true}};
  const std::string dir = test::temp_dir("openmesh-written");
  for (const Kind& k : kinds) {
    const std::string name = k.name, ext = name.substr(name.rfind('.'));
    const std::string written = dir + "/tmp" + ext, path = dir + "/fern" + ext;
    ASSERT_TRUE(OpenMesh::IO::write_mesh(tm, written, O(k.flags))) << k.name;
    std::filesystem::rename(written, path);  // the mesh is named after the file
    const Scene s = load_scene(path);
    ASSERT_EQ(s.meshes.size(), 1u) << k.name;
    expect_same(want, s.meshes[0], k);
    EXPECT_NEAR(s.bounds().diagonal(), bounds.diagonal(), 1e-5f) << k.name;
    EXPECT_TRUE(s.report.warnings.empty()) << k.name << ": " << s.report.warnings.front();
  }
}

}  // namespace
}  // namespace sylva
