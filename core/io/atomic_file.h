// Writing output files so a failure never leaves a half-written file: bytes go to a temporary
// file in the target folder, renamed into place only when complete.
#pragma once

#include <string>

namespace sylva {

// Throws InputError(path, "cannot write: <reason>") when the folder is missing or
// unwritable; the temporary file is removed on every failure.
void write_file_atomic(const std::string& path, const std::string& bytes);

// Reads a whole file. Throws InputError(path, "no such file" / "cannot read: ...").
std::string read_file_bytes(const std::string& path);

}  // namespace sylva
