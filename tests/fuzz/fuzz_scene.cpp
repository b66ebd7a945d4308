// A scene file (.glb, .gltf, .obj, .ply, .off or .stl: SYLVA_FUZZ_EXT chooses) through
// load_scene, as `sylva render FILE` reads it. A loaded scene must hold what the renderer
// relies on: indices in range, finite unit normals, finite positions and attributes of the
// right lengths, valid material and texture references, textures of width * height * 4 bytes;
// plants and instances that pass validate_instances with an id layout that fits 32 bits, and
// cameras with finite, usable parameters.
// For the mesh formats, what is accepted is what the text says: each loaded mesh written as OBJ
// text (tests/obj_text.h) reads back as the same mesh, and an OBJ input of at most 16 KiB is
// accepted or refused (on the same line) as the independent reference reader
// (tests/obj_reference.h) does, with the same mesh when accepted.
#include <cmath>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "core/scene/gltf_nodes.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "core/scene/mesh_formats.h"
#include "tests/fuzz/fuzz_support.h"
#include "tests/obj_reference.h"
#include "tests/obj_text.h"

#ifndef SYLVA_FUZZ_EXT
#error "SYLVA_FUZZ_EXT (the file extension, e.g. \".glb\") must be defined"
#endif

namespace {

using sylva::fuzz::fail;

constexpr std::string_view kExt = SYLVA_FUZZ_EXT;
constexpr bool kMeshFormat = kExt == ".obj" || kExt == ".ply" || kExt == ".off" || kExt == ".stl";
constexpr size_t kReferenceBytes = 16384;

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_mesh(const sylva::Scene& scene, const sylva::Mesh& m) {
  const size_t n = m.positions.size();
  if (m.indices.empty() || m.indices.size() % 3 != 0) fail("mesh " + m.name + ": index count");
  for (uint32_t i : m.indices)
    if (i >= n) fail("mesh " + m.name + ": index out of range");
  for (const glm::vec3& p : m.positions)
    if (!finite(p)) fail("mesh " + m.name + ": non-finite position");
  if (m.normals.size() != n) fail("mesh " + m.name + ": normal count");
  for (const glm::vec3& v : m.normals)
    if (!finite(v) || std::abs(glm::length(v) - 1.0f) > 1e-3f)
      fail("mesh " + m.name + ": normal not finite and unit");
  if (!m.uvs.empty() && m.uvs.size() != n) fail("mesh " + m.name + ": uv count");
  for (const glm::vec2& t : m.uvs)
    if (!std::isfinite(t.x) || !std::isfinite(t.y)) fail("mesh " + m.name + ": non-finite uv");
  if (!m.colors.empty() && m.colors.size() != n) fail("mesh " + m.name + ": colour count");
  if (!m.ka.empty() && m.ka.size() != n) fail("mesh " + m.name + ": ka count");
  for (float k : m.ka)
    if (!(k >= 0.0f && k <= 1.0f)) fail("mesh " + m.name + ": ka outside [0, 1]");
  if (m.roles.size() != m.triangle_count() || m.primitive_ids.size() != m.triangle_count())
    fail("mesh " + m.name + ": per-triangle arrays");
  if (m.material < -1 || m.material >= int(scene.materials.size()))
    fail("mesh " + m.name + ": material index");
}

void check_instances(const sylva::Scene& scene) {
  try {
    sylva::validate_instances(scene, "fuzz");
    sylva::id_layout(scene);
  } catch (const sylva::InputError& e) {
    fail(std::string("a loaded scene's instancing: ") + e.what());
  }
  if (scene.instanced() && scene.instances.size() > sylva::kMaxInstances) fail("instance count");
}

void check_cameras(const sylva::Scene& scene) {
  for (const sylva::SceneCamera& c : scene.cameras) {
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(c.to_world[i / 4][i % 4])) fail("camera " + c.name + ": transform");
    const bool ok = c.orthographic
                        ? c.xmag > 0.0f && c.ymag > 0.0f && c.znear >= 0.0f && c.zfar > c.znear
                        : c.yfov > 0.0f && c.yfov < 3.1416f && c.znear > 0.0f &&
                              (c.zfar == 0.0f || c.zfar > c.znear);
    if (!ok || !std::isfinite(c.zfar) || !std::isfinite(c.ymag)) fail("camera " + c.name);
  }
}

void check_scene(const sylva::Scene& scene) {
  if (scene.meshes.empty()) fail("a loaded scene without meshes");
  check_instances(scene);
  check_cameras(scene);
  for (const sylva::Mesh& m : scene.meshes)
    check_mesh(scene, m);
  for (const sylva::Material& mat : scene.materials) {
    if (mat.base_color_texture < -1 || mat.base_color_texture >= int(scene.textures.size()))
      fail("material " + mat.name + ": texture index");
    if (!(mat.alpha_cutoff >= 0.0f && mat.alpha_cutoff <= 1.0f)) fail("alpha cutoff");
  }
  for (const sylva::Texture& t : scene.textures)
    if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * t.height * 4)
      fail("texture " + t.name + ": size");
}

// The loaded mesh as OBJ text, read again: the same positions, triangles and colours (OBJ has
// no alpha), and the same uvs and normals on every vertex a triangle uses (OBJ gives a vertex
// only what a face corner names).
void check_round_trip(const sylva::Mesh& m) {
  sylva::MeshData d;
  try {
    d = sylva::read_obj(sylva::test::obj_text(m), "round-trip.obj");
  } catch (const sylva::InputError& e) {
    fail(std::string("mesh " + m.name + " written as OBJ is refused: ") + e.what());
  }
  if (d.positions != m.positions || d.indices != m.indices)
    fail("mesh " + m.name + " written as OBJ reads back other positions or triangles");
  if (d.colors.size() != m.colors.size()) fail("mesh " + m.name + ": colours lost as OBJ");
  for (size_t i = 0; i < m.colors.size(); ++i)
    if (glm::vec3(d.colors[i]) != glm::vec3(m.colors[i]))
      fail("mesh " + m.name + ": colour " + std::to_string(i) + " changed as OBJ");
  if (d.uvs.size() != m.uvs.size() || d.normals.size() != m.normals.size())
    fail("mesh " + m.name + ": uvs or normals lost as OBJ");
  for (uint32_t v : m.indices)
    if ((!m.uvs.empty() && d.uvs[v] != m.uvs[v]) || d.normals[v] != m.normals[v])
      fail("mesh " + m.name + ": vertex " + std::to_string(v) + "'s uv or normal changed as OBJ");
}

// The reader and the reference reader agree: both refuse the text on the same line, or both
// read the same mesh.
void check_against_reference(std::string_view text) {
  std::optional<sylva::MeshData> got;
  std::string error;
  try {
    got = sylva::read_obj(text, "in.obj");
  } catch (const sylva::InputError& e) {
    error = e.reason();
  }
  const sylva::test::ObjReference ref = sylva::test::read_obj_reference(text);
  const std::string line = "line " + std::to_string(ref.error_line) + ":";
  if (got && !ref.ok) fail("the reader accepts what the reference refuses at " + line);
  if (!got && ref.ok) fail("the reader refuses what the reference accepts: " + error);
  if (!got && error.compare(0, line.size(), line) != 0)
    fail("the reference refuses at " + line + " the reader says: " + error);
  if (got && (got->positions != ref.mesh.positions || got->indices != ref.mesh.indices ||
              got->uvs != ref.mesh.uvs || got->normals != ref.mesh.normals ||
              got->colors != ref.mesh.colors))
    fail("the reader and the reference read different meshes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sylva::fuzz::write_input(data, size, std::string("in") + SYLVA_FUZZ_EXT);
  sylva::fuzz::expect_input_error([&] {
    const sylva::Scene scene = sylva::load_scene(path);
    check_scene(scene);
    if (kMeshFormat)
      for (const sylva::Mesh& m : scene.meshes)
        check_round_trip(m);
  });
  if (kExt == ".obj" && size <= kReferenceBytes)
    check_against_reference(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
