// OBJ files are read as written or refused (issue 37; core/scene/obj_read.cpp): every number a
// decimal number a float holds finitely with nothing after it, every index a whole number naming
// an element declared before its line; anything else one error naming the line and the token.
// The valid variants (`v x y z w`, `v x y z r g b`, `vt u`, relative indices, ignored keywords)
// read as the text says. Each case is also read by the independent reference reader
// (tests/obj_reference.h), which must agree on the mesh or on the line of the fault.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/scene/load.h"
#include "core/scene/mesh_formats.h"
#include "tests/obj_reference.h"
#include "tests/obj_text.h"
#include "tests/test_support.h"

namespace sylva {
namespace {

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // lines 1-3

std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = test::temp_dir("obj-strict") + "/" + name;
  test::write_file(path, bytes);
  return path;
}

// The error's text after "<path>: ", which must be one line; the reference reader must fault on
// the line the error names.
std::string error_of(const std::string& text) {
  const std::string path = write("bad.obj", text);
  try {
    load_scene(path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    const test::ObjReference ref = test::read_obj_reference(text);
    EXPECT_FALSE(ref.ok) << what;
    EXPECT_EQ("line " + std::to_string(ref.error_line) + ":",
              what.substr(path.size() + 2, what.find(':', path.size() + 2) - path.size() - 1))
        << what;
    return what.substr(path.size() + 2);
  }
  ADD_FAILURE() << text << " loaded";
  return "";
}

// The reader's mesh, which the reference reader must read the same.
MeshData read(const std::string& text) {
  MeshData m = read_obj(text, "t.obj");
  const test::ObjReference ref = test::read_obj_reference(text);
  EXPECT_TRUE(ref.ok) << text;
  EXPECT_EQ(ref.mesh.positions, m.positions);
  EXPECT_EQ(ref.mesh.normals, m.normals);
  EXPECT_EQ(ref.mesh.uvs, m.uvs);
  EXPECT_EQ(ref.mesh.colors, m.colors);
  EXPECT_EQ(ref.mesh.indices, m.indices);
  return m;
}

const std::string kVertexRange =
    "expected a vertex index (1 to 3, or -1 to -3 counting back "
    "from the last 'v'), got ";

TEST(ObjStrict, IndicesBeyond32BitsAreRefusedNotWrapped) {
  EXPECT_EQ(error_of(kTriangle + "f 1 2 4294967296\n"), "line 4: " + kVertexRange + "'4294967296'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 4294967299\n"), "line 4: " + kVertexRange + "'4294967299'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 18446744073709551619\n"),
            "line 4: " + kVertexRange + "'18446744073709551619'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 99999999999999999999\n"),
            "line 4: " + kVertexRange + "'99999999999999999999'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 -4294967299\n"),
            "line 4: " + kVertexRange + "'-4294967299'");
}

TEST(ObjStrict, IndicesAreWholeNumbersWithNothingAfterThem) {
  EXPECT_EQ(error_of(kTriangle + "f 1 2 1.5\n"), "line 4: " + kVertexRange + "'1.5'");
  EXPECT_EQ(error_of(kTriangle + "f +1 2 3\n"), "line 4: " + kVertexRange + "'+1'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 3x\n"), "line 4: " + kVertexRange + "'3x'");
  EXPECT_EQ(error_of(kTriangle + "f 0 1 2\n"), "line 4: " + kVertexRange + "'0'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 -\n"), "line 4: " + kVertexRange + "'-'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 3 \\\n1\n"), "line 4: " + kVertexRange + "'\\'");
}

TEST(ObjStrict, RelativeIndicesNameWhatCameBefore) {
  // The message shows the token, not the index it would have wrapped to (4294967296).
  EXPECT_EQ(error_of(kTriangle + "f 1 2 -5\n"), "line 4: " + kVertexRange + "'-5'");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n"),
            "line 3: expected a vertex index (1 to 2, or -1 to -2 counting back from the last "
            "'v'), got '3'");
  EXPECT_EQ(error_of("f 1 2 3\n" + kTriangle),
            "line 1: expected a vertex index of a 'v' line before this one (there is none), got "
            "'1'");
  const MeshData m = read(kTriangle + "f -3 -2 -1\nv 1 1 0\nf -3 -1 -2\n");
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  // Leading zeros are a whole number's (the reference reader's length check once forgot them:
  // found by fuzz_obj, tests/fuzz/regressions/obj/index-with-leading-zeros).
  const MeshData zeros = read(kTriangle + "f 0000000000000000000000000000003 -0002 01\n");
  EXPECT_EQ(zeros.indices, (std::vector<uint32_t>{2, 1, 0}));
}

TEST(ObjStrict, FacesNeedThreeCorners) {
  EXPECT_EQ(error_of(kTriangle + "f\n"),
            "line 4: expected a face of at least 3 corners, got 0 in 'f'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2\n"),
            "line 4: expected a face of at least 3 corners, got 2 in 'f 1 2'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 # 3\n"),
            "line 4: expected a face of at least 3 corners, got 2 in 'f 1 2'");
}

TEST(ObjStrict, CornersNameOnlyDeclaredUvsAndNormals) {
  EXPECT_EQ(error_of(kTriangle + "f 1/1/1 2//2 3\n"),
            "line 4: expected a texture coordinate index of a 'vt' line before this one (there "
            "is none), got '1' in '1/1/1'");
  EXPECT_EQ(error_of(kTriangle + "vt 0 0\nf 1/1/1 2/1 3/1\n"),
            "line 5: expected a normal index of a 'vn' line before this one (there is none), got "
            "'1' in '1/1/1'");
  EXPECT_EQ(error_of(kTriangle + "vt 0 0\nf 1/1 2/2 3/1\n"),
            "line 5: expected a texture coordinate index (1 to 1, or -1 to -1 counting back "
            "from the last 'vt'), got '2' in '2/2'");
  EXPECT_EQ(error_of(kTriangle + "vn 0 0 1\nf 1// 2//1 3//1\n"),
            "line 5: expected a normal index (1 to 1, or -1 to -1 counting back from the last "
            "'vn'), got '' in '1//'");
  EXPECT_EQ(error_of(kTriangle + "vt 0 0\nf 1/ 2/1 3/1\n"),
            "line 5: expected a texture coordinate index (1 to 1, or -1 to -1 counting back "
            "from the last 'vt'), got '' in '1/'");
  EXPECT_EQ(error_of(kTriangle + "f /1 2 3\n"), "line 4: " + kVertexRange + "'' in '/1'");
  EXPECT_EQ(error_of(kTriangle + "vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n"),
            "line 6: expected a face corner 'v', 'v/vt', 'v//vn' or 'v/vt/vn', got '1/1/1/1'");
}

TEST(ObjStrict, VerticesHaveThreeFourOrSixNumbers) {
  EXPECT_EQ(error_of("v 1 2\n"),
            "line 1: expected 'v x y z', 'v x y z w' or 'v x y z r g b', got 'v 1 2'");
  EXPECT_EQ(error_of("v 1 2 3 4 5 6 7\n"),
            "line 1: expected 'v x y z', 'v x y z w' or 'v x y z r g b', got 'v 1 2 3 4 5 6 7'");
  EXPECT_EQ(error_of("v 1 2 3 4 5\n"),
            "line 1: expected 'v x y z', 'v x y z w' or 'v x y z r g b', got 'v 1 2 3 4 5'");
  EXPECT_EQ(error_of(kTriangle + "vt\n"),
            "line 4: expected 'vt u', 'vt u v' or 'vt u v w', got 'vt'");
  EXPECT_EQ(error_of(kTriangle + "vn 0 1\n"), "line 4: expected 'vn x y z', got 'vn 0 1'");
  EXPECT_EQ(error_of("v 0 0 0 junk\n"), "line 1: expected a number, got 'junk'");
}

TEST(ObjStrict, NumbersAreFiniteDecimalFloats) {
  const std::string finite = "expected a finite number (magnitude at most 3.4e38), got ";
  EXPECT_EQ(error_of("v nan 0 0\n"), "line 1: " + finite + "'nan'");
  EXPECT_EQ(error_of("v 0 -inf 0\n"), "line 1: " + finite + "'-inf'");
  EXPECT_EQ(error_of("v 0 0 infinity\n"), "line 1: " + finite + "'infinity'");
  EXPECT_EQ(error_of("v 1e39 0 0\n"), "line 1: " + finite + "'1e39'");
  EXPECT_EQ(error_of("v 1e400 0 0\n"), "line 1: " + finite + "'1e400'");
  EXPECT_EQ(error_of(kTriangle + "vt 0 1e39\n"), "line 4: " + finite + "'1e39'");
  EXPECT_EQ(error_of(kTriangle + "vn 0 0 -1e39\n"), "line 4: " + finite + "'-1e39'");
  EXPECT_EQ(error_of("v 0 0 0 1 nan 0\n"), "line 1: " + finite + "'nan'");
  EXPECT_EQ(error_of("v 0x1p3 0 0\n"), "line 1: expected a number, got '0x1p3'");
  EXPECT_EQ(error_of("v 0 0 0\nv 1,5 0 0\n"), "line 2: expected a number, got '1,5'");
  EXPECT_EQ(error_of("v +-1 0 0\n"), "line 1: expected a number, got '+-1'");
  EXPECT_EQ(error_of("v 1e 0 0\n"), "line 1: expected a number, got '1e'");
  EXPECT_EQ(error_of("v . 0 0\n"), "line 1: expected a number, got '.'");
  // Signs, points and exponents as C writes them; below a float's range is 0.
  const MeshData m = read("v +1 -.5 5.\nv 1e-400 -0 1E+2\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(m.positions[0], glm::vec3(1.0f, -0.5f, 5.0f));
  EXPECT_EQ(m.positions[1], glm::vec3(0.0f, 0.0f, 100.0f));
}

TEST(ObjStrict, ANulByteIsRefused) {
  EXPECT_EQ(error_of(kTriangle + std::string("f 1 2\0 3\n", 9)),
            "line 4: expected text, got a NUL byte in '2?'");
  EXPECT_EQ(error_of(kTriangle + "f 1 2 3\n# a comment " + std::string(1, '\0') + "\n"),
            "line 5: expected text, got a NUL byte in '?'");
}

TEST(ObjStrict, WeightsAndColoursAreRead) {
  const MeshData w = read("v 0 0 0 1\nv 1 0 0 0.5\nv 0 1 0 2\nf 1 2 3\n");
  EXPECT_EQ(w.positions[2], glm::vec3(0.0f, 1.0f, 0.0f));  // w weights curves only
  EXPECT_TRUE(w.colors.empty());
  const MeshData c = read("v 0 0 0 1 0.5 0\nv 1 0 0 0 1 2\nv 0 1 0 -1 0 0.25\nf 1 2 3\n");
  ASSERT_EQ(c.colors.size(), 3u);
  EXPECT_EQ(c.colors[0], glm::vec4(1.0f, 0.5f, 0.0f, 1.0f));
  EXPECT_EQ(c.colors[1], glm::vec4(0.0f, 1.0f, 1.0f, 1.0f));  // clamped to [0, 1]
  EXPECT_EQ(c.colors[2], glm::vec4(0.0f, 0.0f, 0.25f, 1.0f));
  EXPECT_TRUE(read("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").colors.empty());  // not all
}

TEST(ObjStrict, UvsAndNormalsComeFromTheFirstCornerNamingThem) {
  const MeshData m = read(kTriangle +
                          "v 1 1 0\nvt 0.25\nvt 0.5 0.75 1\nvn 0 0 1\nvn 0 1 0\n"
                          "f 1/1/2 2/2/1 3//1\nf 3/2 2/1 4/-1/-2\n");
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_EQ(m.uvs[0], glm::vec2(0.25f, 0.0f));
  EXPECT_EQ(m.uvs[1], glm::vec2(0.5f, 0.75f));  // not the second face's vt 1
  EXPECT_EQ(m.uvs[2], glm::vec2(0.5f, 0.75f));  // the first face named none for vertex 3
  ASSERT_EQ(m.normals.size(), 4u);
  EXPECT_EQ(m.normals[0], glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(m.normals[3], glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST(ObjStrict, OtherStatementsAreIgnoredAndPolygonsAreFans) {
  const MeshData m = read(
      "# a comment\r\nmtllib leaf.mtl /dev/zero\r\no plant\r\ng leaf\r\ns off\r\n"
      "usemtl green\r\nvp 0.5 x\r\nsomething 1 2 3\r\nV 1 2\r\n" +
      std::string("v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nv 0.5 1.5 0 # apex\r\n") +
      "l 1 2\r\np 3\r\nf 1 2 3 4 5 # pentagon\r\n\r\n   \t\r\nf 4 3 2\r\n");
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 3, 2, 1}));
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_EQ(m.skipped_faces, 0u);
  // A UTF-8 byte order mark is not part of the first line's keyword.
  const MeshData bom = read("\xEF\xBB\xBF" + kTriangle + "f 1 2 3\n");
  EXPECT_EQ(bom.positions[0], glm::vec3(0.0f));
  EXPECT_EQ(bom.indices, (std::vector<uint32_t>{0, 1, 2}));
}

// A mesh read by the strict reader, written as OBJ and read again, is the same mesh.
TEST(ObjStrict, WrittenAndReadAgainIsTheSame) {
  const MeshData m =
      read(kTriangle + "v 0.1 0.2 0.3\nvt 0.1 0.9\nvn 0 0 1\nf 1/1/1 2/1/1 4/1/1\nf -4 -3 -2\n");
  const MeshData again = read(test::obj_text(m));
  EXPECT_EQ(again.positions, m.positions);
  EXPECT_EQ(again.uvs, m.uvs);
  EXPECT_EQ(again.normals, m.normals);
  EXPECT_EQ(again.indices, m.indices);
}

// The shared fern, written as one OBJ by this test, reads back to the same triangles.
TEST(ObjStrict, TheFernAsObjReadsBackTheSame) {
  const Scene fern = load_scene(test::fern_path());
  MeshData all;
  bool uvs = true;
  for (const Mesh& m : fern.meshes)
    uvs = uvs && m.uvs.size() == m.positions.size();
  for (const Mesh& m : fern.meshes) {
    for (uint32_t i : m.indices)
      all.indices.push_back(i + uint32_t(all.positions.size()));
    all.positions.insert(all.positions.end(), m.positions.begin(), m.positions.end());
    all.normals.insert(all.normals.end(), m.normals.begin(), m.normals.end());
    if (uvs) all.uvs.insert(all.uvs.end(), m.uvs.begin(), m.uvs.end());
  }
  const Scene s = load_scene(write("fern.obj", test::obj_text(all)));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), fern.triangle_count());
  EXPECT_EQ(s.meshes[0].indices, all.indices);
  EXPECT_EQ(s.meshes[0].positions, all.positions);
  EXPECT_EQ(s.meshes[0].uvs, all.uvs);
  EXPECT_TRUE(s.report.warnings.empty()) << s.report.warnings.front();
}

}  // namespace
}  // namespace sylva
