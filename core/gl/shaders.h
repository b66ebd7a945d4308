// GLSL 4.50 sources of the G-buffer raster pass and the helpers that compile and link them.
// Conventions shared with rasterizer.cpp: vertex attribute locations (kAttrib*), fragment
// output location i = colour-attachment slot i = the i-th entry of kAllTargets, and one
// program variant per target mask, alpha test and instancing (#define OUT_COLOR ... /
// ALPHA_TEST / INSTANCED prepended; flat scenes draw with the variant without instancing): a pass
// that does not write colour skips the lighting, and opaque meshes get a shader without `discard`,
// which lets llvmpipe test depth before shading.
#pragma once

#include "core/gl/gl_api.h"

#include <string>

#include "core/gl/gbuffer.h"

namespace sylva {

// Vertex attribute locations.
inline constexpr GLuint kAttribPosition = 0;  // vec3, world space
inline constexpr GLuint kAttribNormal = 1;    // vec3, world space, length = ka (Luft et al.)
inline constexpr GLuint kAttribUv = 2;        // vec2, glTF convention (v down)
inline constexpr GLuint kAttribColor = 3;     // vec4, linear RGBA vertex colour
inline constexpr GLuint kAttribIds = 4;       // uvec2 (primitive id, cluster id)
inline constexpr GLuint kAttribRole = 5;      // uint (Role)
inline constexpr GLuint kAttribKa = 6;        // float ambient coefficient; < 0: use |normal|
// Per instance, in the INSTANCED variant (core/gl/instance_draws.h).
inline constexpr GLuint kAttribModel = 7;          // mat4 (7 to 10), plant space -> world
inline constexpr GLuint kAttribNormalMatrix = 11;  // mat3 (11 to 13)
inline constexpr GLuint kAttribIdBase = 14;        // uvec4: primitive, cluster, object bases; plant

// The full fragment/vertex source for a target mask (with "#version 450 core" and defines);
// `instanced` adds the per-instance attributes (#define INSTANCED).
std::string raster_vertex_source(bool instanced = false);
std::string raster_fragment_source(TargetMask targets, bool alpha_test, bool instanced = false);

// The fragment shader's ambient visibility functions (core/gl/shader_ao.cpp).
std::string raster_ao_glsl();

// Compiles one stage; throws std::runtime_error with the info log on failure.
GLuint compile_shader(GLenum stage, const std::string& source, const std::string& name);
// Links (and deletes) the stages; throws std::runtime_error with the info log on failure.
GLuint link_program(GLuint vertex, GLuint fragment, const std::string& name);
// compile_shader + link_program for the raster pass of this target mask.
GLuint build_raster_program(TargetMask targets, bool alpha_test, bool instanced = false);

// A raster program variant and its uniform locations (-1 when optimised away).
struct RasterProgram {
  GLuint id = 0;
  GLint view, proj, id_kind, only_cluster, object_id, branch_cluster, base_color, has_texture,
      texture, alpha_cutoff, double_sided, has_normals, ortho, ambient, light_count, light_vector,
      light_color, light_spec, scaled_normals, oriented_foliage, flat_albedo, texture_mean,
      ao_model, ao_constant, ao_alpha_rho, ao_shell_count, ao_centre, ao_anchor, ao_inverse,
      ao_transpose, ao_volume_scale, ao_crown, ao_exact_solid_angle, ao_grass, ao_ground, ao_grid,
      ao_grid_cells;
};
RasterProgram make_raster_program(TargetMask targets, bool alpha_test, bool instanced = false);

}  // namespace sylva
