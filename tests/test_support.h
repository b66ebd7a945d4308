// Helpers shared by the test programs: where the shared assets and the sylva binary are,
// temporary directories, running the CLI and capturing its output.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace sylva::test {

std::string shared_dir();  // ../shared (CMake SYLVA_SHARED_DIR)
std::string source_dir();
std::string fern_path();  // shared/assets/polyhaven_fern_02.glb
std::string sylva_binary();

// A fresh empty directory under the build's temp area, removed at process exit.
std::string temp_dir(const std::string& tag);

struct RunResult {
  int status = -1;     // exit status
  std::string output;  // stdout + stderr
};
// Runs a shell command (stderr joined to stdout), e.g. a tool nobody here wrote that checks an
// output: rsvg-convert, xmllint, pdftoppm.
RunResult run_command(const std::string& command);
// Runs `sylva <args>` through /bin/sh (args are passed verbatim), with SYLVA_CACHE_DIR set
// to a folder of the test run, so tests never read or fill the user's cache.
RunResult run_sylva(const std::string& args);
// Runs the Khronos glTF Validator (tests/tools/validate_gltf.mjs under node) on a .glb or
// .gltf: output is "errors=N warnings=N" and the error messages, status 0 without errors.
RunResult validate_gltf(const std::string& path);
// Whether scripts/setup.sh installed the validator (npm, tests/tools/node_modules).
bool gltf_validator_installed();

// The `where` of the InputError that f throws, or "no error".
std::string where_of(const std::function<void()>& f);

// The number of newlines in s (one-line error messages are checked with it).
int count_lines(const std::string& s);

std::string read_file(const std::string& path);
void write_file(const std::string& path, const std::string& bytes);
bool file_exists(const std::string& path);

// Sets an environment variable (nullopt: unsets it) for the scope, for this process and the
// commands it runs (SYLVA_GL, ...); restores the old value after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::optional<std::string>& value);
  ~ScopedEnv();
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* m_name;
  std::optional<std::string> m_old;
};

}  // namespace sylva::test
