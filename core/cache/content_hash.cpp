#include "core/cache/content_hash.h"

#include <xxhash.h>

#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace sylva {

ContentHash::ContentHash() : m_state(XXH3_createState()) {
  SYLVA_CHECK(m_state != nullptr, "out of memory");
  XXH3_128bits_reset(static_cast<XXH3_state_t*>(m_state));
}

ContentHash::~ContentHash() {
  XXH3_freeState(static_cast<XXH3_state_t*>(m_state));
}

void ContentHash::add_bytes(const void* data, size_t size) {
  if (size > 0) XXH3_128bits_update(static_cast<XXH3_state_t*>(m_state), data, size);
}

void ContentHash::add(const std::string& text) {
  add(uint64_t(text.size()));
  add_bytes(text.data(), text.size());
}

template <>
void ContentHash::add<double>(const double& value) {
  const double v = value == 0.0 ? 0.0 : value;
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  add(bits);
}

template <>
void ContentHash::add<float>(const float& value) {
  add(double(value));
}

std::string ContentHash::hex() const {
  const XXH128_hash_t h = XXH3_128bits_digest(static_cast<XXH3_state_t*>(m_state));
  char buf[33];
  std::snprintf(buf, sizeof buf, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return buf;
}

}  // namespace sylva
