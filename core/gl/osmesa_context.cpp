#include "core/gl/osmesa_context.h"

#include <GL/osmesa.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace sylva {

namespace {

constexpr int kClientSize = 4;  // pixels per side of the unused client buffer

class OsmesaContext final : public GlContext {
 public:
  OsmesaContext() : m_client_buffer(size_t(kClientSize * kClientSize * 4), 0) {
    // OSMesa hands out 4.5 core for a 3.3 or 4.5 request; 4.6 fails. No default framebuffer
    // depth: every pass renders into its own FBO.
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_STENCIL_BITS,
                           0,
                           OSMESA_ACCUM_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    m_context = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!m_context) throw std::runtime_error("cannot create an OpenGL 4.5 core context");
    GlInfo info;
    info.backend = GlBackend::Osmesa;
    info.platform = "osmesa";
    info.device = "software";
    info.window_system = "OSMesa";
    try {
      load(&OSMesaGetProcAddress, info);
    } catch (...) {
      release();
      OSMesaDestroyContext(m_context);
      throw;
    }
  }

  ~OsmesaContext() override {
    release();
    OSMesaDestroyContext(m_context);
  }

 private:
  void bind() override {
    if (!OSMesaMakeCurrent(m_context, m_client_buffer.data(), GL_UNSIGNED_BYTE, kClientSize,
                           kClientSize))
      throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
  }
  void unbind() override { OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0); }
  bool bound() const override { return OSMesaGetCurrentContext() == m_context; }

  OSMesaContext m_context = nullptr;
  std::vector<uint8_t> m_client_buffer;  // 4 x 4 RGBA8, never read
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context() {
  return std::make_unique<OsmesaContext>();
}

}  // namespace sylva
