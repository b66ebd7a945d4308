// The OSMesa (llvmpipe) backend of GlContext: a 4.5 core profile context bound to a tiny
// client colour buffer that nothing draws into (OSMesaMakeCurrent requires one even though
// all rendering goes to FBOs). Its gl* functions come from OSMesaGetProcAddress (core/gl/
// gl_api.h), so linking libOpenGL for EGL beside it does not matter. LP_NUM_THREADS
// (rasteriser threads) is left to the user; llvmpipe defaults to the number of cores.
#pragma once

#include <memory>

#include "core/gl/gl_context.h"

namespace sylva {

// Throws std::runtime_error when OSMesa cannot create a 4.5 core context.
std::unique_ptr<GlContext> create_osmesa_context();

}  // namespace sylva
