// An offscreen OpenGL 4.5 core context from one of two backends, and the choice between them.
// The rest of the code renders into its own FBOs and never calls a window-system API.
//   EGL     the device platform first (eglQueryDevicesEXT: a GPU when there is one, or the
//           device SYLVA_EGL_DEVICE / `--gl egl:N` names), then Mesa's surfaceless platform
//           (llvmpipe on the CPU where there is no GPU). No display or surface: FBOs only.
//   OSMesa  Mesa's llvmpipe through libOSMesa (removed from Mesa in 25.1).
// Either may be left out of the build (SYLVA_EGL, SYLVA_OSMESA in CMake). Every gl* call goes
// through the functions the current context's backend loaded (core/gl/gl_api.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace sylva {

struct GlApi;
using GlProc = void (*)();
using GlGetProc = GlProc (*)(const char* name);  // OSMesaGetProcAddress, eglGetProcAddress

enum class GlBackend { Auto, Egl, Osmesa };

// "auto", "egl", "osmesa".
const char* gl_backend_name(GlBackend backend);
// The backends this build has, in the order auto tries them.
std::vector<GlBackend> built_gl_backends();

// The EGL devices as `sylva info --gl` lists them ("0: /dev/dri/renderD128", "1: software");
// empty without EGL or devices.
std::vector<std::string> egl_devices();

// Which backend to start. `where` names the setting it came from ("--gl", "SYLVA_GL") for
// error messages.
struct GlChoice {
  GlBackend backend = GlBackend::Auto;
  int egl_device = -1;  // EGL: index into eglQueryDevicesEXT's list; -1 = a GPU, else surfaceless
  std::string where = "SYLVA_GL";
};

// "auto", "egl", "egl:N" (N in [0, 999]) or "osmesa". Throws InputError(where, ...) otherwise.
GlChoice parse_gl_choice(const std::string& text, const std::string& where);
// `option` (a --gl value, where "--gl") or, when it is empty, SYLVA_GL (unset or empty: auto);
// then SYLVA_EGL_DEVICE (a device index) unless the value was egl:N. Throws InputError("--gl",
// "SYLVA_GL" or "SYLVA_EGL_DEVICE", ...) for a bad value.
GlChoice gl_choice_from_option(const std::string& option);
// gl_choice_from_option("").
GlChoice gl_choice_from_environment();

// What a context runs on, for `sylva info --gl` and --verbose.
struct GlInfo {
  GlBackend backend = GlBackend::Auto;
  std::string platform;  // EGL: "device" or "surfaceless"; OSMesa: "osmesa"
  // EGL device: "1 of 2, /dev/dri/renderD128" or "0 of 1, software"; surfaceless: what
  // Mesa picked; OSMesa: "software".
  std::string device;
  std::string vendor, renderer, version;  // GL_VENDOR, GL_RENDERER, GL_VERSION
  std::string window_system;              // "EGL 1.5 (Mesa Project)", "OSMesa"
  bool software = false;                  // a CPU rasteriser (llvmpipe, softpipe, swrast)
  // auto: why the backends it tried first did not start ("" when the first one did).
  std::string fallback;
};

class GlContext {
 public:
  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread and its backend's functions the ones the
  // gl* names call there; the context current before it (another backend's too) is released.
  void make_current();
  // Leaves no context current on the calling thread (when this one is), so that another thread
  // may make it current next (one scene rendered from several threads: the Python module).
  void release_current() { release(); }
  const GlInfo& info() const { return m_info; }
  // "EGL surfaceless / llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile) Mesa 22.3.6"
  std::string description() const;

 protected:
  GlContext();
  // The backend's constructor calls this once its native context exists: binds it, loads every
  // function of gl_api.h through `get_proc`, reads the GL strings into `info`. Throws
  // std::runtime_error naming the functions the backend lacks.
  void load(GlGetProc get_proc, GlInfo info);
  // The backend's destructor calls this before it destroys the native context.
  void release();

  virtual void bind() = 0;  // the native make-current on this thread; throws on failure
  virtual void unbind() = 0;
  virtual bool bound() const = 0;  // natively current on this thread

 private:
  friend std::unique_ptr<GlContext> create_gl_context(const GlChoice& choice);
  std::unique_ptr<GlApi> m_api;
  GlInfo m_info;
};

// Starts the backend `choice` names; auto tries EGL, then OSMesa. A backend this build lacks or
// that does not start is InputError(choice.where, ...) with the reason (both reasons for auto).
std::unique_ptr<GlContext> create_gl_context(const GlChoice& choice);
// The choice of the environment (gl_choice_from_environment()).
std::unique_ptr<GlContext> create_gl_context();

}  // namespace sylva
