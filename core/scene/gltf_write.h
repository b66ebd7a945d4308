// Writing a scene as binary glTF 2.0 (.glb): one node and mesh per Scene mesh (positions in
// world space), materials with base colour factor/texture (PNG-embedded), alpha mode,
// double-sidedness; the plant hierarchy and per-triangle ids in extras. Output passes the
// Khronos glTF Validator with 0 errors. Written atomically (temp file + rename).
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

void write_glb(const Scene& scene, const std::string& path);

}  // namespace sylva
