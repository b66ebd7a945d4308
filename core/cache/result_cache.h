// The on-disk cache of preprocessing results (DESIGN.md §3): one file per result, named by
// its kind and content key (core/cache/content_hash.h), so a second render of the same scene
// with the same parameters and code reads the result instead of recomputing it. Files are
// written atomically and checked when read (magic, key, lengths): a missing, truncated or
// corrupted entry is a cache miss, never a crash. Nothing is evicted: delete the folder to
// reclaim space.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace sylva {

// $SYLVA_CACHE_DIR, else $XDG_CACHE_HOME/sylva, else $HOME/.cache/sylva; "" when none is set.
std::string default_cache_dir();

class ResultCache {
 public:
  explicit ResultCache(std::string dir) : m_dir(std::move(dir)) {}
  const std::string& dir() const { return m_dir; }
  std::string path(const std::string& kind, const std::string& key) const;

  // The payload stored for (kind, key), or nullopt when absent, unreadable or damaged.
  std::optional<std::string> load(const std::string& kind, const std::string& key) const;
  // Creates the folder if needed and writes atomically. A cache that cannot be written only
  // costs time, so this returns false with the reason instead of throwing.
  bool store(const std::string& kind, const std::string& key, const std::string& payload,
             std::string* why = nullptr) const;

 private:
  std::string m_dir;
};

// Little helpers to serialise plain arrays into a payload and read them back with bounds
// checks (a short or inconsistent payload makes the reader fail, not overrun).
class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    m_bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(uint64_t(v.size()));
    if (!v.empty())  // an empty vector's data() may be null, which append must not be given
      m_bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string take() { return std::move(m_bytes); }

 private:
  std::string m_bytes;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : m_bytes(bytes) {}
  template <class T>
  bool get(T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (m_bytes.size() - m_pos < sizeof v) return false;
    std::memcpy(&v, m_bytes.data() + m_pos, sizeof v);
    m_pos += sizeof v;
    return true;
  }
  template <class T>
  bool get(std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint64_t n = 0;
    if (!get(n) || n > (m_bytes.size() - m_pos) / sizeof(T)) return false;
    v.resize(size_t(n));
    if (n == 0) return true;  // memcpy must not be given an empty vector's null data()
    std::memcpy(v.data(), m_bytes.data() + m_pos, size_t(n) * sizeof(T));
    m_pos += size_t(n) * sizeof(T);
    return true;
  }
  bool done() const { return m_pos == m_bytes.size(); }

 private:
  const std::string& m_bytes;
  size_t m_pos = 0;
};

}  // namespace sylva
