#include "tests/test_support.h"

#include "core/error.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace fs = std::filesystem;

namespace sylva::test {

std::string shared_dir() {
  return SYLVA_SHARED_DIR;
}
std::string source_dir() {
  return SYLVA_SOURCE_DIR;
}
std::string fern_path() {
  return shared_dir() + "/assets/polyhaven_fern_02.glb";
}
std::string sylva_binary() {
  return SYLVA_BINARY;
}

namespace {
struct TempRoot {
  fs::path root;
  TempRoot() {
    std::string tmpl = (fs::temp_directory_path() / "sylva-test-XXXXXX").string();
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed");
    root = buf.data();
  }
  ~TempRoot() {
    std::error_code ec;
    if (!std::getenv("SYLVA_KEEP_TEST_FILES")) fs::remove_all(root, ec);
  }
};
TempRoot& temp_root() {
  static TempRoot r;
  return r;
}
}  // namespace

std::string temp_dir(const std::string& tag) {
  static int counter = 0;
  fs::path p = temp_root().root / (tag + "-" + std::to_string(counter++));
  fs::create_directories(p);
  return p.string();
}

RunResult run_command(const std::string& command) {
  RunResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw std::runtime_error("popen failed");
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0)
    r.output.append(buf.data(), n);
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

RunResult run_sylva(const std::string& args) {
  // The CLI caches preprocessing results; tests keep theirs in their own temporary folder.
  static const bool cache_set =
      setenv("SYLVA_CACHE_DIR", (temp_root().root / "cache").c_str(), 1) == 0;
  (void)cache_set;
  return run_command(sylva_binary() + " " + args);
}

RunResult validate_gltf(const std::string& path) {
  return run_command("node " + source_dir() + "/tests/tools/validate_gltf.mjs " + path);
}

bool gltf_validator_installed() {
  return fs::exists(source_dir() + "/tests/tools/node_modules/gltf-validator/package.json");
}

std::string where_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.where();
  }
  return "no error";
}

int count_lines(const std::string& s) {
  return int(std::count(s.begin(), s.end(), '\n'));
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

bool file_exists(const std::string& path) {
  return fs::exists(path);
}

ScopedEnv::ScopedEnv(const char* name, const std::optional<std::string>& value) : m_name(name) {
  if (const char* old = std::getenv(name)) m_old = old;
  if (value)
    setenv(name, value->c_str(), 1);
  else
    unsetenv(name);
}

ScopedEnv::~ScopedEnv() {
  if (m_old)
    setenv(m_name, m_old->c_str(), 1);
  else
    unsetenv(m_name);
}

}  // namespace sylva::test
