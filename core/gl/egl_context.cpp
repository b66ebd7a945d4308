#include "core/gl/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace sylva {

namespace {

std::string egl_error(const std::string& what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", unsigned(eglGetError()));
  return what + " failed (EGL error " + code + ")";
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// The client extensions' entry points (null where absent).
struct EglClient {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC platform_display = nullptr;
  bool surfaceless = false;  // EGL_MESA_platform_surfaceless
  bool device_platform = false;

  EglClient() {
    const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_extension(ext, "EGL_EXT_platform_base"))
      platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
          eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (has_extension(ext, "EGL_EXT_device_enumeration")) {
      query_devices =
          reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
      query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
          eglGetProcAddress("eglQueryDeviceStringEXT"));
    }
    surfaceless = platform_display && has_extension(ext, "EGL_MESA_platform_surfaceless");
    device_platform = platform_display && query_devices && query_device_string &&
                      has_extension(ext, "EGL_EXT_platform_device");
  }

  std::vector<EGLDeviceEXT> devices() const {
    if (!device_platform) return {};
    EGLint n = 0;
    if (!query_devices(0, nullptr, &n) || n <= 0) return {};
    std::vector<EGLDeviceEXT> out(static_cast<size_t>(n));
    if (!query_devices(n, out.data(), &n)) return {};
    out.resize(size_t(n));
    return out;
  }

  bool software(EGLDeviceEXT device) const {
    return has_extension(query_device_string(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
  }

  // "/dev/dri/renderD128", "software".
  std::string node(EGLDeviceEXT device) const {
    const char* node = software(device) ? "software" : "no DRM node";
    const char* ext = query_device_string(device, EGL_EXTENSIONS);
    const char* file = nullptr;
    if (has_extension(ext, "EGL_EXT_device_drm_render_node"))
      file = query_device_string(device, EGL_DRM_RENDER_NODE_FILE_EXT);
    if (!file && has_extension(ext, "EGL_EXT_device_drm"))
      file = query_device_string(device, EGL_DRM_DEVICE_FILE_EXT);
    return file ? file : node;
  }
};

class EglContext final : public GlContext {
 public:
  // Throws std::runtime_error saying why `display` gives no context.
  EglContext(EGLDisplay display, const std::string& platform, std::string device)
      : m_display(display) {
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY) throw std::runtime_error(egl_error("eglGetPlatformDisplay"));
    if (!eglInitialize(display, &major, &minor))
      throw std::runtime_error(egl_error("eglInitialize"));
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_surfaceless_context"))
      throw std::runtime_error("no EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(egl_error("eglBindAPI(OpenGL)"));
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(ext, "EGL_KHR_no_config_context")) {
      const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
      EGLint n = 0;
      if (!eglChooseConfig(display, wanted, &config, 1, &n) || n < 1)
        throw std::runtime_error("no EGL config renders OpenGL");
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    m_context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (m_context == EGL_NO_CONTEXT)
      throw std::runtime_error(egl_error("eglCreateContext(OpenGL 4.5 core)"));
    GlInfo info;
    info.backend = GlBackend::Egl;
    info.platform = platform;
    info.device = std::move(device);
    const char* vendor = eglQueryString(display, EGL_VENDOR);
    info.window_system = "EGL " + std::to_string(major) + "." + std::to_string(minor) + " (" +
                         (vendor ? vendor : "?") + ")";
    if (has_extension(ext, "EGL_MESA_query_driver")) {
      auto driver = reinterpret_cast<PFNEGLGETDISPLAYDRIVERNAMEPROC>(
          eglGetProcAddress("eglGetDisplayDriverName"));
      const char* name = driver ? driver(display) : nullptr;
      if (name) info.device += (info.device.empty() ? "driver " : ", driver ") + std::string(name);
    }
    try {
      load(&eglGetProcAddress, info);
    } catch (...) {
      release();
      eglDestroyContext(m_display, m_context);
      throw;
    }
  }

  ~EglContext() override {
    release();
    eglDestroyContext(m_display, m_context);
  }

 private:
  void bind() override {
    eglBindAPI(EGL_OPENGL_API);
    if (!eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, m_context))
      throw std::runtime_error(egl_error("eglMakeCurrent"));
  }
  void unbind() override {
    eglBindAPI(EGL_OPENGL_API);
    eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  bool bound() const override {
    eglBindAPI(EGL_OPENGL_API);
    return eglGetCurrentContext() == m_context;
  }

  EGLDisplay m_display = EGL_NO_DISPLAY;
  EGLContext m_context = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> create_egl_context(int device) {
  const EglClient client;
  const std::vector<EGLDeviceEXT> devices = client.devices();
  const size_t n = devices.size();
  auto on_device = [&](size_t i) {
    const EGLDisplay display =
        client.platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    return std::make_unique<EglContext>(
        display, "device",
        std::to_string(i) + " of " + std::to_string(n) + ", " + client.node(devices[i]));
  };
  if (device >= 0) {
    if (size_t(device) >= n)
      throw std::runtime_error(
          "no EGL device " + std::to_string(device) + " (" +
          (client.device_platform ? std::to_string(n) + " found" : "no EGL_EXT_platform_device") +
          ")");
    return on_device(size_t(device));
  }
  std::string tried;
  auto attempt = [&tried](const std::string& what, auto&& make) -> std::unique_ptr<GlContext> {
    try {
      return make();
    } catch (const std::runtime_error& e) {
      tried += (tried.empty() ? "" : "; ") + what + ": " + e.what();
      return nullptr;
    }
  };
  for (size_t i = 0; i < n; ++i)
    if (!client.software(devices[i]))
      if (auto c = attempt("device " + std::to_string(i), [&] { return on_device(i); })) return c;
  if (client.surfaceless)
    if (auto c = attempt("surfaceless", [&] {
          const EGLDisplay display =
              client.platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
          return std::make_unique<EglContext>(display, "surfaceless", "");
        }))
      return c;
  for (size_t i = 0; i < n; ++i)
    if (client.software(devices[i]))
      if (auto c = attempt("device " + std::to_string(i), [&] { return on_device(i); })) return c;
  if (tried.empty())
    tried = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS)
                ? "neither EGL devices nor the surfaceless platform"
                : "no EGL client extensions (no EGL vendor library?)";
  throw std::runtime_error(tried);
}

std::vector<std::string> list_egl_devices() {
  const EglClient client;
  std::vector<std::string> out;
  for (EGLDeviceEXT device : client.devices())
    out.push_back(std::to_string(out.size()) + ": " + client.node(device));
  return out;
}

}  // namespace sylva
