// Loading the sylva_codecs plugin on first use; see codecs.h.
#include "core/io/codecs.h"

#include <dlfcn.h>

#include <algorithm>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <opencv2/imgcodecs.hpp>  // the enums only: the functions are in the plugin
#include <stdexcept>
#include <string>
#include <vector>

#include "core/io/codecs_jpeg.h"
#include "core/io/codecs_png.h"

namespace sylva {

namespace {

constexpr const char* kPluginName = "libsylva_codecs.so";

bool starts_with(const unsigned char* bytes, size_t size, const char* magic, size_t n) {
  return size >= n && std::memcmp(bytes, magic, n) == 0;
}

// The formats decode_image leaves to OpenCV, by their signatures: TIFF (both byte orders), BMP,
// WebP (a RIFF "WEBP" file), PNM (P1-P7), OpenEXR and Radiance HDR.
bool is_plugin_format(const unsigned char* b, size_t size) {
  return starts_with(b, size, "II*\0", 4) || starts_with(b, size, "MM\0*", 4) ||
         starts_with(b, size, "BM", 2) ||
         (starts_with(b, size, "RIFF", 4) && size >= 12 && std::memcmp(b + 8, "WEBP", 4) == 0) ||
         (size >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') ||
         starts_with(b, size, "\x76\x2f\x31\x01", 4) || starts_with(b, size, "#?RADIANCE", 10) ||
         starts_with(b, size, "#?RGBE", 6);
}

struct Loaded {
  const CodecsApi* api = nullptr;
  std::string path;   // where it was loaded from
  std::string error;  // why it did not load, when api is null
};

// Where to look, in order: $SYLVA_CODECS (an explicit choice wins), beside the executable,
// SYLVA_CODECS_INSTALL_PATH relative to the executable's folder (where `cmake --install` and
// the .deb put it, e.g. ../lib/x86_64-linux-gnu/sylva/), then, for programs inside the build tree
// only (the tests, build/cli/sylva), SYLVA_CODECS_BUILD_PATH, the module's path there; all compiled
// in by core/CMakeLists.txt. An installed or copied sylva never looks into the tree it was built
// in.
std::vector<std::string> candidates() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("SYLVA_CODECS"); env && *env) paths.push_back(env);
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return paths;
  paths.push_back((exe.parent_path() / kPluginName).string());
#ifdef SYLVA_CODECS_INSTALL_PATH
  paths.push_back((exe.parent_path() / SYLVA_CODECS_INSTALL_PATH).lexically_normal().string());
#endif
#if defined(SYLVA_CODECS_BUILD_PATH) && defined(SYLVA_BUILD_DIR)
  // /proc/self/exe has no symbolic links; the build folder's path may.
  const std::string build_dir =
      std::filesystem::weakly_canonical(SYLVA_BUILD_DIR, ec).string() + "/";
  if (!ec && exe.string().starts_with(build_dir) &&
      std::find(paths.begin(), paths.end(), SYLVA_CODECS_BUILD_PATH) == paths.end())
    paths.push_back(SYLVA_CODECS_BUILD_PATH);
#endif
  return paths;
}

Loaded load() {
  Loaded out;
  std::string tried;
  for (const std::string& path : candidates()) {
    // Never closed: OpenCV keeps global state (backends, thread pools) until exit.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      tried += "; " + std::string(why ? why : path + ": dlopen failed");
      continue;
    }
    using Entry = const CodecsApi* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, kCodecsApiSymbol));
    const CodecsApi* api = entry ? entry() : nullptr;
    if (api && api->version == kCodecsApiVersion) {
      out.api = api;
      out.path = path;
      return out;
    }
    tried += "; " + path + ": " +
             (entry ? "built for another version of sylva" : std::string("no ") + kCodecsApiSymbol);
  }
  // One line, as main() prints it: "sylva: failed: cannot load ...".
  out.error = std::string("cannot load the codecs plugin ") + kPluginName +
              " (needed for images other than PNG and for video; set SYLVA_CODECS to its path)" +
              tried;
  return out;
}

// The plugin, loaded on the first call (thread-safe).
const Loaded& loaded() {
  static std::once_flag once;
  static Loaded l;
  std::call_once(once, [] { l = load(); });
  return l;
}

}  // namespace

const CodecsApi& codecs() {
  const Loaded& l = loaded();
  if (!l.api) throw std::runtime_error(l.error);
  return *l.api;
}

const std::string& codecs_path() {
  codecs();
  return loaded().path;
}

cv::Mat decode_png_or_jpeg(const unsigned char* bytes, size_t size, DecodeReport* report,
                           unsigned long long max_pixels) {
  if (!bytes || size == 0 || size >= size_t(1) << 31) return cv::Mat();
  if (is_png(bytes, size)) return decode_png(bytes, size, report, max_pixels);
  if (is_jpeg(bytes, size)) return decode_jpeg(bytes, size, report, max_pixels);
  return cv::Mat();
}

cv::Mat decode_image(const unsigned char* bytes, size_t size, DecodeReport* report) {
  if (!bytes || size == 0 || size >= size_t(1) << 31) return cv::Mat();
  if (is_png(bytes, size) || is_jpeg(bytes, size)) return decode_png_or_jpeg(bytes, size, report);
  if (!is_plugin_format(bytes, size)) return cv::Mat();
  const cv::Mat encoded(1, int(size), CV_8U, const_cast<unsigned char*>(bytes));
  return codecs().decode(encoded, cv::IMREAD_UNCHANGED);
}

}  // namespace sylva
