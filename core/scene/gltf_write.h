// Writing a scene as binary glTF 2.0 (.glb): one node and mesh per Scene mesh (positions in
// world space), materials with base colour factor/texture (PNG-embedded), alpha mode,
// double-sidedness; the plant hierarchy (scenes[0].extras.sylva_hierarchy) and roles in
// extras ("sylva_role" on the mesh, or on each primitive when a mesh mixes roles: such a mesh
// then has one primitive per role and reads back as one Mesh per role). Primitive and cluster
// ids are not stored: the loader recomputes them deterministically. Normals are written unit
// length (an ambient coefficient encoded in their length is dropped); indices are 16-bit
// when they fit. Output follows the rules the Khronos glTF Validator checks (POSITION
// min/max, 4-byte aligned views, PNG textures). Written atomically (temp file + rename);
// failures throw InputError(path, "cannot write: ...").
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

void write_glb(const Scene& scene, const std::string& path);

}  // namespace sylva
