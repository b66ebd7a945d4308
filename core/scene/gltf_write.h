// Writing a scene as binary glTF 2.0 (.glb): one node and mesh per Scene mesh (positions in
// world space); an instanced scene keeps its instancing: one glTF mesh per Scene mesh (in
// plant space) and per instance a node with its transform ("matrix") and extras
// "sylva_plant" = the plant's name (so it reads back as that plant even when placed once),
// with a child node per plant mesh sharing them, the plant's hierarchy on its first
// instance's node. Scene::cameras become glTF cameras placed by root nodes of their names.
// Materials with base colour factor/texture (PNG-embedded), alpha mode, double-sidedness; the
// plant hierarchy (scenes[0].extras.sylva_hierarchy) and roles in extras ("sylva_role" on the
// mesh, or on each primitive when a mesh mixes roles: such a mesh then has one primitive per
// role and reads back as one Mesh per role). Primitive and cluster ids are not stored: the
// loader recomputes them deterministically. Normals are written unit length (an ambient
// coefficient encoded in their length is dropped); indices are 16-bit when they fit. Output
// follows the rules the Khronos glTF Validator checks (POSITION min/max, 4-byte aligned views,
// PNG textures). Written atomically (temp file + rename); failures throw
// InputError(path, "cannot write: ...").
//
// Ambient coefficients (`sylva bake`, Luft et al. §3.2 ka) travel as three attributes so both
// Sylva and other engines can use them: "_AMBIENT" (SCALAR float, ka in [0, 1]; the glTF
// spec's application-specific attribute), COLOR_0 = ka x the mesh's own vertex colour (VEC3
// float; engines that multiply the base colour by COLOR_0 darken the crown), and the mesh's
// own vertex colours, when it has some, moved to COLOR_1 (VEC4). Such a mesh's extras carry
// "sylva_color_0": "ambient", so the reader restores the colours from COLOR_1 rather than
// taking the darkened preview for real colours.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

// Per-vertex data written in place of (or next to) what the scene's meshes carry. Each outer
// vector is indexed like Scene::meshes; an empty outer vector means "use the mesh's own".
struct GlbVertexData {
  // Written as NORMAL (normalized; the glTF spec requires unit normals) instead of the mesh's
  // normals. Per mesh, one per vertex. Such meshes (and those with Mesh::outward_normals) are
  // marked extras.sylva_normals = "outward", which the reader turns back into
  // Mesh::outward_normals.
  std::vector<std::vector<glm::vec3>> normals;
  // Ambient coefficient per vertex, each in [0, 1], written as described above instead of
  // Mesh::ka. Per mesh, one per vertex.
  std::vector<std::vector<float>> ka;
  // A JSON object (text) stored as scenes[0].extras.sylva_baked, e.g. the parameters that made
  // the data; empty = none.
  std::string note_json;
};

// Without `extra`, a mesh's own normals and (when present) Mesh::ka are written. A programming
// error (SYLVA_CHECK) when `extra`'s arrays do not match the scene's meshes and vertices or ka
// leaves [0, 1].
void write_glb(const Scene& scene, const std::string& path, const GlbVertexData* extra = nullptr);

}  // namespace sylva
