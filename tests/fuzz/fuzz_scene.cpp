// A scene file (.glb, .gltf, .obj, .ply, .off or .stl: SYLVA_FUZZ_EXT chooses) through
// load_scene, as `sylva render FILE` reads it. A loaded scene must hold what the renderer
// relies on: indices in range, finite unit normals, finite positions and attributes of the
// right lengths, valid material and texture references, textures of width * height * 4 bytes;
// plants and instances that pass validate_instances with an id layout that fits 32 bits, and
// cameras with finite, usable parameters.
#include <cmath>

#include "core/error.h"
#include "core/scene/gltf_nodes.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "tests/fuzz/fuzz_support.h"

#ifndef SYLVA_FUZZ_EXT
#error "SYLVA_FUZZ_EXT (the file extension, e.g. \".glb\") must be defined"
#endif

namespace {

using sylva::fuzz::fail;

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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sylva::fuzz::write_input(data, size, std::string("in") + SYLVA_FUZZ_EXT);
  sylva::fuzz::expect_input_error([&] { check_scene(sylva::load_scene(path)); });
  return 0;
}
