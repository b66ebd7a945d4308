#include "core/versions.h"

#include <cairo.h>
#include <gif_lib.h>
#include <png.h>

#include <cstdio>
#include <exception>
#include <glm/glm.hpp>
#include <opencv2/core/utility.hpp>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <openexr_base.h>

#include "core/gl/gl_context.h"
#include "core/io/codecs.h"

namespace sylva {

namespace {

std::string gl_version() {
  try {
    return create_gl_context()->description();
  } catch (const std::exception& e) {
    return std::string("unavailable: ") + e.what();
  }
}

#define SYLVA_STRINGIFY2(x) #x
#define SYLVA_STRINGIFY(x) SYLVA_STRINGIFY2(x)

std::string jpeg_version() {
#ifdef LIBJPEG_TURBO_VERSION
  return "libjpeg-turbo " SYLVA_STRINGIFY(LIBJPEG_TURBO_VERSION) ", API " +
         std::to_string(JPEG_LIB_VERSION) + " (build)";
#else
  return "API " + std::to_string(JPEG_LIB_VERSION) + " (build)";
#endif
}

std::string openexr_version() {
  int major = 0, minor = 0, patch = 0;
  const char* extra = nullptr;
  exr_get_library_version(&major, &minor, &patch, &extra);
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch) +
         (extra && *extra ? std::string("-") + extra : "");
}

std::string codecs_version() {
  try {
    const CodecsApi& api = codecs();
    return codecs_path() + " (" + api.versions() + ")";
  } catch (const std::exception& e) {
    return std::string("unavailable: ") + e.what();
  }
}

}  // namespace

std::vector<LibraryVersion> core_library_versions() {
  return {
      {"OpenCV", cv::getVersionString()},
      {"OpenGL", gl_version()},
      {"OpenEXR", openexr_version()},
      {"cairo", cairo_version_string()},
      {"libpng", png_get_libpng_ver(nullptr)},
      {"libjpeg", jpeg_version()},
      {"giflib", std::to_string(GIFLIB_MAJOR) + "." + std::to_string(GIFLIB_MINOR) + "." +
                     std::to_string(GIFLIB_RELEASE) + " (build)"},
      {"GLM", std::to_string(GLM_VERSION_MAJOR) + "." + std::to_string(GLM_VERSION_MINOR) + "." +
                  std::to_string(GLM_VERSION_PATCH) + " (build)"},
      {"codecs plugin", codecs_version()},
  };
}

}  // namespace sylva
