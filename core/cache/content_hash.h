// Content hashing for the preprocessing cache (DESIGN.md §3): a streaming 128-bit XXH3 over
// the bytes that determine a result (mesh data, parameters, a code version). Fields are added
// one by one, with their sizes, so two different inputs never hash the same concatenation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace sylva {

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  void add_bytes(const void* data, size_t size);
  // A trivially copyable value without padding (scalars, glm vectors), hashed as its bytes.
  template <class T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "hash the fields one by one");
    add_bytes(&value, sizeof value);
  }
  void add(const std::string& text);
  template <class T>
  void add(const std::vector<T>& values) {
    add(uint64_t(values.size()));
    if constexpr (std::is_trivially_copyable_v<T>) {
      add_bytes(values.data(), values.size() * sizeof(T));
    } else {
      for (const T& v : values)
        add(v);
    }
  }
  // 32 lowercase hex digits.
  std::string hex() const;

 private:
  void* m_state;
};

// Single doubles and floats (parameters) are hashed by value with -0 folded into +0.
template <>
void ContentHash::add<double>(const double& value);
template <>
void ContentHash::add<float>(const float& value);

}  // namespace sylva
