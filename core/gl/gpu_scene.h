// Scene upload for the raster pass: one VAO per mesh (positions, normals, UVs, colours,
// per-vertex primitive/cluster ids and role, indices) and sRGB mipmapped textures. Runs in
// the current GL context; the caller owns the returned objects.
#pragma once

#include "core/gl/gl_api.h"

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

struct GpuMesh {
  GLuint vao = 0;
  std::vector<GLuint> buffers;
  GLsizei index_count = 0;
  int material = -1;
  uint32_t object_id = 0;    // the id buffer's object id (instanced: index in its plant + 1)
  uint32_t scene_index = 0;  // index into Scene::meshes
  bool has_normals = false;
  size_t vertex_count = 0;
  GLuint normal_buffer = 0;  // replaceable (replace_shading); 0 = none
  GLuint ka_buffer = 0;
  bool oriented_foliage = false;  // foliage normals replaced by outward ones (Luft §3.3)
};

// Throws InputError when a per-vertex or per-triangle array has the wrong length or an
// index is out of range. object_id is the mesh's 1-based id in object ID buffers.
GpuMesh upload_mesh(const Mesh& mesh, uint32_t object_id);
void release_mesh(GpuMesh& mesh);

// Replaces a mesh's per-vertex normals (empty: none, flat shading) and ambient coefficients
// (empty: decoded from the normal length). Throws InputError naming the mesh on a count
// that does not match its vertices.
void replace_shading(GpuMesh& mesh, const std::vector<glm::vec3>& normals,
                     const std::vector<float>& ka, const std::string& name);

// Throws InputError when the pixel data does not match the size.
GLuint upload_texture(const Texture& tex);

// The mean linear colour of the texels with alpha >= 0.5 (a leaf card's leaf, not its
// transparent surround); all texels when none is.
glm::vec3 texture_mean(const Texture& t);

// An immutable GL_NEAREST-filtered 2D texture of one level, for a framebuffer attachment.
GLuint make_target_texture(GLenum internal_format, int width, int height);

// What a mesh without a material is drawn with.
Material default_material();

}  // namespace sylva
