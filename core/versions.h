// The versions of the libraries the core links, for `sylva --version --verbose`: what the
// library reports at run time where it can (OpenCV, OpenEXR, cairo, libpng, the GL renderer),
// else the version this build was compiled against, marked "(build)".
#pragma once

#include <string>
#include <vector>

namespace sylva {

struct LibraryVersion {
  std::string name;     // "OpenCV"
  std::string version;  // "4.6.0"
};

// OpenCV, the GL context (backend, renderer and version string, from a context created for the
// purpose; the reason when none can be had), OpenEXR, cairo, libpng, libjpeg, giflib, GLM, and
// the codecs plugin (its path and FFmpeg's version, or why it does not load).
std::vector<LibraryVersion> core_library_versions();

}  // namespace sylva
