// Whether a material draws at a texture coordinate: alpha-cutout leaves (glTF alphaMode MASK
// or BLEND with a base-colour texture) are drawn where the texel's alpha times the material's
// reaches the cutoff (MASK: alphaCutoff; BLEND: 0.5, as the raster pass draws it). Nearest
// texel, repeat wrapping. What the ray tracer and the surface samples both decide, so they
// agree with the raster pass about which parts of a card are leaf.
#pragma once

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace sylva {

// The material has a base-colour texture whose alpha cuts its shape out (MASK or BLEND).
bool is_cutout(const Scene& scene, const Material& material);

// False where a cutout material's texel is below the cutoff; true otherwise (opaque
// materials, no texture, an empty texture).
bool drawn_at(const Scene& scene, const Material& material, glm::vec2 uv);

}  // namespace sylva
