// What `sylva --version` prints: the version and the git commit it was built from
// ("sylva 0.1.0 (commit fc025d0a1b2c)"; "-dirty" when the checkout had uncommitted changes,
// "unknown" outside a git checkout). With --verbose also the compiler and the libraries'
// versions: OpenCV, the GL renderer, OpenEXR, Embree, ... (core/versions.h, npr/versions.h).
#pragma once

#include <string>

namespace sylva::cli {

// "sylva 0.1.0 (commit fc025d0a1b2c)", no newline.
std::string version_line();

// version_line(), then one line per library ("OpenCV         4.6.0"). Creates a GL context, an
// Embree device and loads the codecs plugin to ask them; a part that cannot be had says why.
std::string version_report();

}  // namespace sylva::cli
