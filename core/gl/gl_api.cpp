#include "core/gl/gl_api.h"

#include <cstdio>
#include <stdexcept>

#include "core/error.h"

namespace sylva {

namespace {

[[noreturn]] void no_gl_context() {
  check_failed("a current GlContext", __FILE__, __LINE__,
               "a gl* function was called on a thread with no Sylva GL context current "
               "(GlContext::make_current)");
}

// What a gl* name calls while no context is current on the thread.
template <class F>
struct Unloaded;
template <class R, class... A>
struct Unloaded<R (*)(A...)> {
  static R call(A...) { no_gl_context(); }
};

}  // namespace

#define SYLVA_GL_DEFINE(type, name) thread_local constinit type name = &Unloaded<type>::call;
SYLVA_GL_FUNCTIONS(SYLVA_GL_DEFINE)
#undef SYLVA_GL_DEFINE

std::string load_gl_api(GlApi& api, GlGetProc get_proc) {
  std::string missing;
#define SYLVA_GL_LOAD(type, name)                     \
  api.name = reinterpret_cast<type>(get_proc(#name)); \
  if (!api.name) missing += (missing.empty() ? "" : " ") + std::string(#name);
  SYLVA_GL_FUNCTIONS(SYLVA_GL_LOAD)
#undef SYLVA_GL_LOAD
  return missing;
}

void check_gl_errors(const std::string& what) {
  // Drain the flags (an implementation may hold several), report the first.
  const GLenum first = glGetError();
  for (int n = 0; n < 16 && glGetError() != GL_NO_ERROR; ++n) {
  }
  if (first == GL_NO_ERROR) return;
  if (first == GL_OUT_OF_MEMORY) throw std::runtime_error(what + ": the GL ran out of memory");
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", first);
  throw std::runtime_error(what + ": GL error " + code);
}

void use_gl_api(const GlApi* api) {
#define SYLVA_GL_USE(type, name) name = api ? api->name : &Unloaded<type>::call;
  SYLVA_GL_FUNCTIONS(SYLVA_GL_USE)
#undef SYLVA_GL_USE
}

}  // namespace sylva
