// An independent minimal OBJ reader for differential checks of core/scene/obj_read.cpp (the
// OBJ tests and the fuzz_obj harness): the same rules (tests/core/scene/test_obj_strict.cpp
// lists them) written again another way: lines split by hand and by std::istringstream,
// numbers checked against the decimal grammar and converted by std::strtod, no TextScan and
// nothing shared with the reader. It says only whether the text is accepted and, if not, on
// which line the first fault is; it does not word errors.
#pragma once

#include <string_view>

#include "core/scene/mesh_data.h"

namespace sylva::test {

struct ObjReference {
  bool ok = false;
  size_t error_line = 0;  // the line of the first fault, when !ok
  MeshData mesh;          // what the text says, when ok
};

ObjReference read_obj_reference(std::string_view text);

}  // namespace sylva::test
