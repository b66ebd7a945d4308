// The EGL backend of GlContext: an OpenGL 4.5 core context with no surface
// (EGL_KHR_surfaceless_context; rendering goes to FBOs). Which display:
//   device >= 0  the device of that index in eglQueryDevicesEXT's list (EGL_EXT_platform_device);
//   device < 0   each device that is not Mesa's software one (a GPU: EGL_MESA_device_software
//                absent) in list order, then Mesa's surfaceless platform (which itself takes a
//                render node when Mesa drives one, else llvmpipe), then the software devices.
// The first display that gives a context wins; the reasons of those that did not are kept in
// the error when none does. Its gl* functions come from eglGetProcAddress (core/gl/gl_api.h).
// Displays are initialised once per process and never terminated: eglTerminate would destroy
// every other context on the same display (eglGetPlatformDisplay hands out one per device), and
// a second eglInitialize loads llvmpipe's LLVM again (~0.1 s).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/gl/gl_context.h"

namespace sylva {

// Throws std::runtime_error saying what was tried when no display gives a context.
std::unique_ptr<GlContext> create_egl_context(int device);
// eglQueryDevicesEXT's devices: "0: /dev/dri/renderD128", "1: software".
std::vector<std::string> list_egl_devices();

}  // namespace sylva
