// Seeded randomness that does not depend on the standard library's distributions (which
// differ between implementations): the splitmix64 stream and uniform doubles from it.
#pragma once

#include <cstdint>

namespace sylva {

// The next number of the splitmix64 stream whose state is `state` (advanced).
inline uint64_t splitmix64(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) with 53 random bits.
inline double uniform01(uint64_t& state) {
  return double(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace sylva
