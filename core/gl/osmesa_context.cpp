#include "core/gl/osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace sylva {

namespace {

constexpr int kClientSize = 4;  // pixels per side of the unused client buffer

OSMesaContext as_osmesa(void* context) {
  return static_cast<OSMesaContext>(context);
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

}  // namespace

OsmesaContext::OsmesaContext()
    : m_client_buffer(static_cast<size_t>(kClientSize * kClientSize * 4), 0) {
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
  OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!context) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
  m_context = context;
  make_current();
  // GL_VERSION carries the Mesa release: "4.5 (Core Profile) Mesa 22.3.6".
  m_description = "OSMesa / " + gl_string(GL_RENDERER) + " / " + gl_string(GL_VERSION);
}

OsmesaContext::~OsmesaContext() {
  if (m_context) OSMesaDestroyContext(as_osmesa(m_context));
}

void OsmesaContext::make_current() {
  if (OSMesaGetCurrentContext() == as_osmesa(m_context)) return;
  if (!OSMesaMakeCurrent(as_osmesa(m_context), m_client_buffer.data(), GL_UNSIGNED_BYTE,
                         kClientSize, kClientSize)) {
    throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
  }
}

void OsmesaContext::release_current() {
  // OSMesaMakeCurrent(NULL, NULL, ...) unbinds; only this context's own binding is undone.
  if (OSMesaGetCurrentContext() == as_osmesa(m_context))
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
}

std::string OsmesaContext::description() const {
  return m_description;
}

std::unique_ptr<GlContext> create_gl_context() {
  return std::make_unique<OsmesaContext>();
}

}  // namespace sylva
