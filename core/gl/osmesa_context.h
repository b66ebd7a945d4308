// The OSMesa (llvmpipe) backend of GlContext: a 4.5 core profile context bound to a tiny
// client colour buffer that nothing draws into (OSMesaMakeCurrent requires one even though
// all rendering goes to FBOs). Link only OSMesa: libGL/libOpenGL ahead of it turns every GL
// call into a silent no-op. LP_NUM_THREADS (rasteriser threads) is left to the user;
// llvmpipe defaults to the number of cores.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/gl/gl_context.h"

namespace sylva {

class OsmesaContext final : public GlContext {
 public:
  // Throws std::runtime_error when OSMesa cannot create a 4.5 core context.
  OsmesaContext();
  ~OsmesaContext() override;
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  void make_current() override;
  void release_current() override;
  std::string description()
      const override;  // "OSMesa / llvmpipe (...) / 4.5 (Core Profile) Mesa 22.3.6"

 private:
  void* m_context = nullptr;             // OSMesaContext (kept opaque to avoid GL headers here)
  std::vector<uint8_t> m_client_buffer;  // 4 x 4 RGBA8, never read
  std::string m_description;
};

}  // namespace sylva
