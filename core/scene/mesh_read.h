// Reading polygon meshes (.obj, .ply, .off, .stl by Sylva's readers, core/scene/mesh_formats.h)
// into the scene model: one Mesh named after the file stem, polygons fan-triangulated, faces
// that cannot be drawn skipped with one warning, vertex normals / texture coordinates / colours
// kept when the file has them (normals computed otherwise), one default material. Bad or empty
// files throw InputError(path, "<what is wrong>").
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace sylva {

Scene read_mesh_file(const std::string& path);

}  // namespace sylva
