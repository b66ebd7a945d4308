// An embedded PNG or JPEG texture through decode_texture (libpng and libjpeg in process, with
// Sylva's error and warning handlers), as a glTF image reaches it. A decoded texture must be
// width * height RGBA texels; a warning must be one line.
#include <vector>

#include "core/scene/texture_decode.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> warnings;
  sylva::fuzz::expect_input_error([&] {
    const sylva::Texture t =
        sylva::decode_texture(data, size, "texture", "fuzz.glb", "image 0", warnings);
    if (t.width <= 0 || t.height <= 0 || t.rgba.size() != size_t(t.width) * t.height * 4)
      sylva::fuzz::fail("decoded texture size");
  });
  for (const std::string& w : warnings)
    if (w.find('\n') != std::string::npos) sylva::fuzz::fail("a warning of several lines: " + w);
  return 0;
}
