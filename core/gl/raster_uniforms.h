// Setting the raster programs' per-frame uniforms (core/gl/shaders.h) from the camera, the
// lights and the request: matrices, id kind, lights in view space, and the AO model's terms.
#pragma once

#include <cstdint>

#include "core/gl/rasterizer.h"
#include "core/gl/shaders.h"

namespace sylva {

// Makes `p` current and sets everything that stays the same for a frame; branch_cluster is
// the instanced scene's one non-foliage cluster id (0 = none, or a flat scene).
void set_frame_uniforms(const RasterProgram& p, const Camera& camera, const Lighting& lighting,
                        const RasterRequest& request, uint32_t branch_cluster);
// Checks the request's ssaa and AO terms: InputError for a value out of range (naming --ssaa or
// the ao.* key), SYLVA_CHECK for malformed shells.
void validate_request(const RasterRequest& request);
// The AoShading terms (core/gl/ao_shading.h) of the current program `p`.
void set_ao_uniforms(const RasterProgram& p, const AoShading& ao);

}  // namespace sylva
