#include "core/cache/result_cache.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/io/atomic_file.h"

namespace fs = std::filesystem;

namespace sylva {

namespace {

constexpr char kMagic[8] = {'S', 'Y', 'L', 'V', 'A', 'C', 'C', '1'};

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

// The header that precedes every payload: magic, kind, key, payload length.
std::string header(const std::string& kind, const std::string& key, uint64_t payload) {
  std::string h(kMagic, sizeof kMagic);
  h += kind + '\n' + key + '\n';
  h.append(reinterpret_cast<const char*>(&payload), sizeof payload);
  return h;
}

}  // namespace

std::string default_cache_dir() {
  if (std::string d = env("SYLVA_CACHE_DIR"); !d.empty()) return d;
  if (std::string d = env("XDG_CACHE_HOME"); !d.empty()) return d + "/sylva";
  if (std::string d = env("HOME"); !d.empty()) return d + "/.cache/sylva";
  return "";
}

std::string ResultCache::path(const std::string& kind, const std::string& key) const {
  return (fs::path(m_dir) / (kind + "-" + key + ".bin")).string();
}

std::optional<std::string> ResultCache::load(const std::string& kind,
                                             const std::string& key) const {
  std::ifstream in(path(kind, key), std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  // The header's length is known once kind and key are; a file that does not start with the
  // expected header (another key, another format, truncated) is a miss.
  const std::string expect = header(kind, key, 0);
  const size_t head = expect.size();
  if (bytes.size() < head ||
      bytes.compare(0, head - sizeof(uint64_t), expect, 0, head - sizeof(uint64_t)) != 0)
    return std::nullopt;
  uint64_t length = 0;
  std::memcpy(&length, bytes.data() + head - sizeof length, sizeof length);
  if (length != bytes.size() - head) return std::nullopt;
  return bytes.substr(head);
}

bool ResultCache::store(const std::string& kind, const std::string& key, const std::string& payload,
                        std::string* why) const {
  try {
    std::error_code ec;
    fs::create_directories(m_dir, ec);
    if (ec) throw InputError(m_dir, "cannot create the cache folder: " + ec.message());
    write_file_atomic(path(kind, key), header(kind, key, payload.size()) + payload);
    return true;
  } catch (const InputError& e) {
    if (why) *why = e.what();
    return false;
  }
}

}  // namespace sylva
