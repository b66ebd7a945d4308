// The polygon mesh formats, each read from the file's bytes into MeshData (core/scene/mesh_data.h);
// read_mesh_file (mesh_read.h) picks one by the file's extension. Malformed files throw
// InputError(path, "<where>: <what is wrong>").
#pragma once

#include <string>
#include <string_view>

#include "core/scene/mesh_data.h"

namespace sylva {

// Wavefront OBJ, strictly (obj_read.cpp): v (with optional w, or r g b), vt, vn, f; other
// statements (materials, groups, lines, points) are ignored. A malformed number or an index
// naming nothing declared before its line is an error.
MeshData read_obj(std::string_view text, const std::string& path);
// Object File Format, ASCII: [ST][C][N]OFF headers, vertex colours as 0-1 floats or 0-255.
MeshData read_off(std::string_view text, const std::string& path);
// Stanford PLY, ASCII and binary (both byte orders): x y z, nx ny nz, u v (or s t), red green
// blue [alpha], and a face list vertex_indices (or vertex_index); other elements are skipped.
MeshData read_ply(std::string_view bytes, const std::string& path);
// STL, ASCII and binary; identical corner positions are welded into one vertex.
MeshData read_stl(std::string_view bytes, const std::string& path);

}  // namespace sylva
