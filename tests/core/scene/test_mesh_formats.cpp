// Sylva's polygon mesh readers (core/scene/mesh_formats.h) on hand-written files: what each
// format's variants load as (positions, normals, uvs, colours, triangles), and the one-line
// errors and warnings of malformed files, with where they are.
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "core/scene/load.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = test::temp_dir("formats") + "/" + name;
  test::write_file(path, bytes);
  return path;
}

std::string error_of(const std::string& name, const std::string& bytes) {
  const std::string path = write(name, bytes);
  try {
    load_scene(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    return what.substr(path.size() + 2);
  }
  ADD_FAILURE() << name << " loaded";
  return "";
}

Mesh only_mesh(const Scene& s) {
  EXPECT_EQ(s.meshes.size(), 1u);
  return s.meshes.at(0);
}

template <class T>
void put(std::string& s, T v, bool big = false) {
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  if (big) std::reverse(b, b + sizeof v);
  s.append(b, sizeof v);
}

// One triangle with normals, uvs and uchar colours, then an extra element, in binary PLY.
std::string binary_ply(bool big) {
  std::string s = std::string("ply\nformat ") +
                  (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\n"
                  "property float y\nproperty double z\nproperty float nx\nproperty float ny\n"
                  "property float nz\nproperty float s\nproperty float t\nproperty uchar red\n"
                  "property uchar green\nproperty uchar blue\nproperty int flags\n"
                  "element face 1\nproperty list uchar uint vertex_indices\nproperty short tag\n"
                  "element edge 1\nproperty list int int ends\nend_header\n";
  for (int i = 0; i < 3; ++i) {
    put(s, float(i == 1), big), put(s, float(i == 2), big), put(s, double(0.5), big);
    put(s, 0.0f, big), put(s, 0.0f, big), put(s, 1.0f, big);
    put(s, 0.25f * float(i), big), put(s, 0.5f, big);
    s += char(255), s += char(0), s += char(51);
    put(s, int32_t(7), big);
  }
  s += char(3);
  for (uint32_t v : {0u, 1u, 2u})
    put(s, v, big);
  put(s, int16_t(-1), big);
  put(s, int32_t(2), big), put(s, int32_t(0), big), put(s, int32_t(1), big);
  return s;
}

TEST(MeshFormats, BinaryPlyInBothByteOrders) {
  for (bool big : {false, true}) {
    const Mesh m = only_mesh(load_scene(write(big ? "big.ply" : "little.ply", binary_ply(big))));
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(m.positions[1], glm::vec3(1.0f, 0.0f, 0.5f));
    EXPECT_EQ(m.positions[2], glm::vec3(0.0f, 1.0f, 0.5f));
    EXPECT_EQ(m.normals[0], glm::vec3(0.0f, 0.0f, 1.0f));
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[2], glm::vec2(0.5f, 0.5f));
    ASSERT_EQ(m.colors.size(), 3u);
    EXPECT_EQ(m.colors[0], glm::vec4(1.0f, 0.0f, 0.2f, 1.0f));
  }
  std::string cut = binary_ply(false);
  cut.resize(cut.size() - 20);
  EXPECT_EQ(error_of("cut.ply", cut), "element 'face' item 1: the file ends here");
}

TEST(MeshFormats, AsciiPlyAndItsErrors) {
  const std::string head =
      "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n"
      "property float z\r\nproperty float alpha\r\nelement face 2\r\n"
      "property list uchar int vertex_index\r\nend_header\r\n";
  const Scene s = load_scene(write("quad.ply", head + "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n"
                                                      "4 0 1 2 3\n3 0 1 7\n"));
  EXPECT_EQ(only_mesh(s).indices.size(), 6u);  // the quad as a fan; the bad triangle skipped
  ASSERT_EQ(s.report.warnings.size(), 1u);
  EXPECT_NE(s.report.warnings[0].find("line 16 (element 'face' item 2): the face has vertex "
                                      "index 7 out of range (4 vertices)"),
            std::string::npos)
      << s.report.warnings[0];
  EXPECT_TRUE(only_mesh(s).colors.empty());  // alpha alone is not a colour
  EXPECT_EQ(error_of("word.ply", head + "0 0 0 1\n1 0 zero 1\n"),
            "line 12: expected a number, got 'zero'");
  EXPECT_EQ(error_of("huge.ply", head + "0 0 0 1\n1 0 1e400 1\n1 1 0 1\n0 1 0 1\n3 0 1 2\n"
                                        "3 0 2 3\n"),
            "vertex 2 has a NaN or infinite position");  // beyond a double: not 0
  EXPECT_EQ(error_of("sign.ply", head + "0 0 0 1\n1 0 +-1 1\n"),
            "line 12: expected a number, got '+-1'");
  EXPECT_EQ(error_of("short.ply", head + "0 0 0 1\n"),
            "line 11: the file ends where a number was expected");
  EXPECT_EQ(error_of("list.ply", head + "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n-3 0 1 2\n"),
            "line 15 (element 'face' item 1): a list length of -3.000000");
  EXPECT_EQ(error_of("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty flt x\n"),
            "line 4: 'flt' is not a PLY property type");
  EXPECT_EQ(error_of("format.ply", "ply\nformat ascii =.0\nend_header\n"),
            "line 2: expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  EXPECT_EQ(error_of("end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n"),
            "the PLY header has no 'end_header'");
  EXPECT_EQ(error_of("empty-element.ply",
                     "ply\nformat ascii 1.0\nelement nothing 4000000000\n"
                     "end_header\n"),
            "line 4: element 'nothing' has 4000000000 items but no properties");
}

TEST(MeshFormats, OffVariants) {
  const Mesh plain = only_mesh(load_scene(write(
      "plain.off", "# no keyword\n4 1 0\n0 0 0\n1 0 0 # a comment\n1 1 0\n0 1 0\n4 0 1 2 3\n")));
  EXPECT_EQ(plain.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  const Mesh full = only_mesh(load_scene(
      write("full.off",
            "STCNOFF 3 1 0\n0 0 0 0 0 1 255 0 0 255 0.5 0.5\n1 0 0 0 0 1 0 255 0 255 1 0\n"
            "0 1 0 0 0 1 0 0 255 255 0 1\n3 0 1 2 1 0 0\n")));
  ASSERT_EQ(full.colors.size(), 3u);
  EXPECT_EQ(full.colors[1], glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));  // 0-255 integers
  EXPECT_EQ(full.uvs[0], glm::vec2(0.5f, 0.5f));
  EXPECT_EQ(full.normals[2], glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(error_of("binary.off", "OFF BINARY\n"), "line 1: binary OFF files are not supported");
  EXPECT_EQ(error_of("4d.off", "4OFF\n1 0 0\n"),
            "line 1: '4OFF' OFF files (4D, nD) are not supported, only 3D");
  EXPECT_EQ(error_of("vertex.off", "NOFF\n1 1 0\n0 0 0\n"),
            "line 3: a vertex line has 3 numbers, expected 6");
  EXPECT_EQ(error_of("faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "line 6: the file ends before all its faces");
  EXPECT_EQ(error_of("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n"),
            "line 6: expected a vertex index (a whole number up to 4294967295), got '-2'");
}

std::string binary_stl(uint32_t triangles, uint32_t claimed) {
  std::string s(80, ' ');
  put(s, claimed);
  for (uint32_t t = 0; t < triangles; ++t) {
    const float corners[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, float(t) + 1.0f,
                               0};  // normal, corners
    s.append(reinterpret_cast<const char*>(corners), sizeof corners);
    s += std::string(2, '\0');
  }
  return s;
}

TEST(MeshFormats, StlBinaryAndAscii) {
  const Mesh b = only_mesh(load_scene(write("two.stl", binary_stl(2, 2))));
  EXPECT_EQ(b.positions.size(), 4u);  // the corners (0,0,0) and (1,0,0) are shared
  EXPECT_EQ(b.indices.size(), 6u);
  const Mesh a = only_mesh(load_scene(
      write("tri.stl",
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
            "vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
            "vertex -0 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid t\n")));
  EXPECT_EQ(a.positions.size(), 4u);  // -0 welds with 0
  EXPECT_EQ(error_of("size.stl", binary_stl(2, 3)).substr(0, 45),
            "not an STL file: binary STL with 3 triangles ");
  EXPECT_EQ(error_of("open.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
            "the ASCII STL file ends without 'endsolid' (cut short?)");
  EXPECT_EQ(error_of("four.stl",
                     "solid t\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                     "vertex 0 0 1\nendloop\nendsolid\n"),
            "line 6: a facet has more than three vertices");
}

TEST(MeshFormats, ObjAttributesAndIndices) {
  const Scene s = load_scene(
      write("uv.obj",
            "mtllib /dev/zero\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\ng leaf\nusemtl green\n"
            "f 1/1/1 2/2/1 3/3/1 4/4/1\nf -4/1 -2/3 -1/4\nl 1 2\n"));
  const Mesh m = only_mesh(s);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 2, 3}));
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[2], glm::vec2(1.0f, 1.0f));
  ASSERT_EQ(m.colors.size(), 4u);
  EXPECT_EQ(m.colors[1], glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
  EXPECT_NEAR(m.normals[0].z, 1.0f, 1e-6f);
  // Colours only when every vertex has them.
  const Mesh some =
      only_mesh(load_scene(write("some.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")));
  EXPECT_TRUE(some.colors.empty());
  // More in test_obj_strict.cpp.
  EXPECT_EQ(error_of("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
            "line 4: expected a vertex index (1 to 3, or -1 to -3 counting back from the last "
            "'v'), got '0'");
  EXPECT_EQ(error_of("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1e39 0\nf 1/1 2/2 3/1\n"),
            "line 5: expected a finite number (magnitude at most 3.4e38), got '1e39'");  // fuzz_obj
  EXPECT_EQ(error_of("points.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"),
            "line 3: expected a face of at least 3 corners, got 2 in 'f 1 2'");
}

}  // namespace
}  // namespace sylva
