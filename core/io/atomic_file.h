// Writing output files so a failure never leaves a half-written file: bytes go to a temporary
// file in the target folder, renamed into place only when complete.
#pragma once

#include <functional>
#include <string>

namespace sylva {

// Throws InputError(path, "cannot write: <reason>") when the folder is missing or
// unwritable; the temporary file is removed on every failure.
void write_file_atomic(const std::string& path, const std::string& bytes);

// A new empty hidden folder beside `path` (".NAME.tmpXXXXXX" in path's folder), for outputs
// made of several files that are put in place together. Throws InputError(path, ...).
std::string make_temporary_folder_beside(const std::string& path);

// Writes a set of files as one: `write(staging)` fills a temporary folder inside `dir`
// (created if missing), whose files are then renamed into `dir`. When `write` throws (a full
// disk, a stop), the staging folder is removed, and `dir` too if this call created it, so no
// part of the set is left. Existing files of the same names are replaced only on success.
void write_folder_atomic(const std::string& dir,
                         const std::function<void(const std::string& staging)>& write);

// Reads a whole file. Throws InputError(path, "no such file" / "cannot read: ...").
std::string read_file_bytes(const std::string& path);

}  // namespace sylva
