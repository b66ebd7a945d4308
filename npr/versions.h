// The versions of the libraries npr links (Embree, OpenMesh, nanoflann, OpenMP), for
// `sylva --version --verbose`; Embree's is the loaded library's, the others this build's.
#pragma once

#include <vector>

#include "core/versions.h"

namespace sylva {

std::vector<LibraryVersion> npr_library_versions();

}  // namespace sylva
