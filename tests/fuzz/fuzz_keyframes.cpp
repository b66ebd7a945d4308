// A blob keyframe cache file's body (npr/blob_keyframes.h, key-NNNNN.txt after its signature
// line) through parse_blob_outlines, as a turntable --resume or a farm job reads a shared
// cache. What parses must be finite and must survive a write and a second read unchanged.
#include <cmath>

#include "npr/blob_keyframes.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sylva::fuzz::expect_input_error([&] {
    const std::vector<sylva::BlobOutline> blobs = sylva::parse_blob_outlines(text, "key");
    const std::string once = sylva::format_blob_outlines(blobs);
    const std::string twice =
        sylva::format_blob_outlines(sylva::parse_blob_outlines(once, "key (written back)"));
    if (once != twice) sylva::fuzz::fail("a keyframe does not survive a write and a read");
  });
  return 0;
}
