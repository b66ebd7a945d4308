// What an image decoder said while decoding: the reason it failed, and its warnings (a corrupt
// but readable stream). libpng and libjpeg print these to stderr unless given handlers; sylva's
// decoders collect them here so the caller reports them in its own words, one line each.
#pragma once

#include <string>
#include <vector>

namespace sylva {

struct DecodeReport {
  std::string error;                  // why decoding failed; empty when it did not or said nothing
  std::vector<std::string> warnings;  // at most kMaxWarnings, in the order the decoder gave them
  static constexpr size_t kMaxWarnings = 1;

  void warn(const std::string& message) {
    if (warnings.size() < kMaxWarnings) warnings.push_back(message);
  }
};

}  // namespace sylva
