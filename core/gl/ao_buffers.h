// The ambient occlusion of a scene of many plants on the GPU (core/gl/ao_shading.h's
// plant_shells and crowns, read by the INSTANCED raster programs, core/gl/shaders.cpp): the
// plants' shells and their ranges, the instances' crowns, and a grid over x and z (at most
// 64 x 64 cells) listing per cell the crowns within kAoCrownReach radii of it, so a fragment
// sums only the crowns near it. Shader storage buffers at bindings 0 to 3. Runs in the current
// GL context; release() before it goes.
#pragma once

#include "core/gl/gl_api.h"

#include <array>
#include <glm/glm.hpp>

#include "core/gl/ao_shading.h"
#include "core/gl/shaders.h"

namespace sylva {

class AoBuffers {
 public:
  // Fills the buffers from `ao` (none, or a flat scene's: empty ones).
  void upload(const AoShading& ao);
  // Binds the buffers and sets the program's grid uniforms.
  void bind(const RasterProgram& program) const;
  void release();

 private:
  std::array<GLuint, 4> m_buffers{};
  glm::vec4 m_grid{0.0f};  // corner x, z, cell size (0: no crowns)
  glm::ivec2 m_cells{0};
};

}  // namespace sylva
