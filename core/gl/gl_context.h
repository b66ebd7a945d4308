// An offscreen OpenGL 4.5 core context. The rest of the code renders into its own FBOs
// through this interface and never calls a window-system API, so another backend (EGL
// surfaceless) can replace OSMesa.
#pragma once

#include <memory>
#include <string>

namespace sylva {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  // Leaves no context current in the calling thread, so that another thread may make this one
  // current next (a program rendering one scene from several threads: the Python module).
  virtual void release_current() = 0;
  virtual std::string description() const = 0;  // "OSMesa 22.3.6 / llvmpipe / 4.5 core"
};

// Creates the default backend (OSMesa). Throws std::runtime_error when no context can be had.
std::unique_ptr<GlContext> create_gl_context();

}  // namespace sylva
