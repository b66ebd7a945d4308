// What a loaded scene holds, as `sylva info --json` prints it and the Python module's
// Scene.info() returns it: triangles (drawn and distinct, by role), instances, plants, leaves,
// clusters, meshes, materials, bounds, cameras, and what the loader decided and warned about.
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

// A JSON object, indented by two spaces, without a final line end.
std::string scene_info_json(const Scene& scene);

}  // namespace sylva
