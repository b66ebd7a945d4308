#include "core/gl/gl_context.h"

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <stdexcept>

#include "core/error.h"
#include "core/gl/gl_api.h"
#if SYLVA_HAVE_EGL
#include "core/gl/egl_context.h"
#endif
#if SYLVA_HAVE_OSMESA
#include "core/gl/osmesa_context.h"
#endif

namespace sylva {

namespace {

// The context whose functions this thread's gl* names call (make_current), if any.
thread_local GlContext* t_current = nullptr;

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

std::string built_list() {
  std::string list;
  for (GlBackend b : built_gl_backends())
    list += (list.empty() ? "" : ", ") + std::string(gl_backend_name(b));
  return list;
}

std::unique_ptr<GlContext> start_backend(GlBackend backend, [[maybe_unused]] int egl_device) {
#if SYLVA_HAVE_EGL
  if (backend == GlBackend::Egl) return create_egl_context(egl_device);
#endif
#if SYLVA_HAVE_OSMESA
  if (backend == GlBackend::Osmesa) return create_osmesa_context();
#endif
  throw std::logic_error(std::string("GL backend not built: ") + gl_backend_name(backend));
}

}  // namespace

const char* gl_backend_name(GlBackend backend) {
  switch (backend) {
    case GlBackend::Egl:
      return "egl";
    case GlBackend::Osmesa:
      return "osmesa";
    case GlBackend::Auto:
      break;
  }
  return "auto";
}

std::vector<GlBackend> built_gl_backends() {
  std::vector<GlBackend> out;
#if SYLVA_HAVE_EGL
  out.push_back(GlBackend::Egl);
#endif
#if SYLVA_HAVE_OSMESA
  out.push_back(GlBackend::Osmesa);
#endif
  return out;
}

std::vector<std::string> egl_devices() {
#if SYLVA_HAVE_EGL
  return list_egl_devices();
#else
  return {};
#endif
}

GlChoice parse_gl_choice(const std::string& text, const std::string& where) {
  GlChoice c;
  c.where = where;
  static const std::regex egl_device(R"(^egl:(\d{1,3})$)");
  std::smatch m;
  if (text == "auto") {
    c.backend = GlBackend::Auto;
  } else if (text == "egl") {
    c.backend = GlBackend::Egl;
  } else if (std::regex_match(text, m, egl_device)) {
    c.backend = GlBackend::Egl;
    c.egl_device = std::stoi(m[1]);
  } else if (text == "osmesa") {
    c.backend = GlBackend::Osmesa;
  } else {
    throw InputError(
        where, "expected auto, egl, egl:N (EGL device N, from 0) or osmesa, got '" + text + "'");
  }
  return c;
}

GlChoice gl_choice_from_option(const std::string& option) {
  const char* gl = std::getenv("SYLVA_GL");
  GlChoice c = !option.empty() ? parse_gl_choice(option, "--gl")
                               : parse_gl_choice(gl && *gl ? gl : "auto", "SYLVA_GL");
  const char* device = std::getenv("SYLVA_EGL_DEVICE");
  if (c.egl_device < 0 && device && *device) {
    static const std::regex digits(R"(^\d{1,3}$)");
    if (!std::regex_match(device, digits))
      throw InputError("SYLVA_EGL_DEVICE",
                       "expected an EGL device index from 0, got '" + std::string(device) + "'");
    c.egl_device = std::stoi(device);
  }
  return c;
}

GlChoice gl_choice_from_environment() {
  return gl_choice_from_option("");
}

GlContext::GlContext() : m_api(std::make_unique<GlApi>()) {}

GlContext::~GlContext() {
  // The backend's destructor has released it already; this only guards a backend that threw.
  if (t_current == this) {
    t_current = nullptr;
    use_gl_api(nullptr);
  }
}

void GlContext::make_current() {
  if (t_current == this && bound()) return;
  if (t_current && t_current != this) t_current->unbind();
  t_current = nullptr;
  use_gl_api(nullptr);
  bind();
  t_current = this;
  use_gl_api(m_api.get());
}

void GlContext::load(GlGetProc get_proc, GlInfo info) {
  if (t_current) t_current->unbind();
  t_current = nullptr;
  use_gl_api(nullptr);
  bind();
  t_current = this;
  const std::string missing = load_gl_api(*m_api, get_proc);
  if (!missing.empty())
    throw std::runtime_error("the GL library lacks functions Sylva calls: " + missing);
  use_gl_api(m_api.get());
  m_info = std::move(info);
  m_info.vendor = gl_string(GL_VENDOR);
  m_info.renderer = gl_string(GL_RENDERER);
  m_info.version = gl_string(GL_VERSION);
  for (const char* cpu : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (m_info.renderer.find(cpu) != std::string::npos) m_info.software = true;
}

void GlContext::release() {
  if (t_current != this) return;
  unbind();
  t_current = nullptr;
  use_gl_api(nullptr);
}

std::string GlContext::description() const {
  std::string backend = m_info.backend == GlBackend::Egl ? "EGL " + m_info.platform : "OSMesa";
  return backend + " / " + m_info.renderer + " / " + m_info.version;
}

std::unique_ptr<GlContext> create_gl_context(const GlChoice& choice) {
  const std::vector<GlBackend> built = built_gl_backends();
  if (choice.backend != GlBackend::Auto) {
    if (std::find(built.begin(), built.end(), choice.backend) == built.end())
      throw InputError(choice.where, std::string("this sylva was built without ") +
                                         gl_backend_name(choice.backend) +
                                         " (built: " + built_list() + ")");
    try {
      return start_backend(choice.backend, choice.egl_device);
    } catch (const std::runtime_error& e) {
      throw InputError(choice.where, std::string(gl_backend_name(choice.backend)) +
                                         " does not start: " + e.what());
    }
  }
  std::string failures;
  for (GlBackend b : built) {
    try {
      std::unique_ptr<GlContext> context = start_backend(b, choice.egl_device);
      context->m_info.fallback = failures;
      return context;
    } catch (const std::runtime_error& e) {
      failures +=
          (failures.empty() ? "" : "; ") + std::string(gl_backend_name(b)) + ": " + e.what();
    }
  }
  throw InputError(choice.where, "no GL backend starts (" + failures + ")");
}

std::unique_ptr<GlContext> create_gl_context() {
  return create_gl_context(gl_choice_from_environment());
}

}  // namespace sylva
