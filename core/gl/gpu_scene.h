// Scene upload for the raster pass: one VAO per mesh (positions, normals, UVs, colours,
// per-vertex primitive/cluster ids and role, indices) and sRGB mipmapped textures. Runs in
// the current GL context; the caller owns the returned objects.
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <cstdint>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

struct GpuMesh {
  GLuint vao = 0;
  std::vector<GLuint> buffers;
  GLsizei index_count = 0;
  int material = -1;
  uint32_t object_id = 0;
  bool has_normals = false;
};

// Throws InputError when a per-vertex or per-triangle array has the wrong length or an
// index is out of range. object_id is the mesh's 1-based id in object ID buffers.
GpuMesh upload_mesh(const Mesh& mesh, uint32_t object_id);
void release_mesh(GpuMesh& mesh);

// Throws InputError when the pixel data does not match the size.
GLuint upload_texture(const Texture& tex);

}  // namespace sylva
