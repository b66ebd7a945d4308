// The option strings a user types: --size, --light, --background and --ground-color (the
// first input byte chooses which; the rest is the text). Accepted values must be in the
// ranges the options document.
#include <cmath>

#include "styles/view.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using sylva::fuzz::fail;

bool unit_colour(const glm::vec4& c) {
  for (int k = 0; k < 4; ++k)
    if (!(c[k] >= 0.0f && c[k] <= 1.0f)) return false;
  return true;
}

void parse(uint8_t which, const std::string& text) {
  switch (which % 4) {
    case 0: {
      int w = 0, h = 0;
      sylva::parse_size(text, w, h);
      if (w < 1 || h < 1 || w > 16384 || h > 16384) fail("--size out of range: " + text);
      break;
    }
    case 1: {
      const sylva::Light l = sylva::parse_light(text);
      const glm::vec3& v = l.vector;
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        fail("--light vector not finite: " + text);
      if (!(l.color.x >= 0.0f && l.color.x <= 10.0f)) fail("--light intensity: " + text);
      if (l.type == sylva::Light::Type::Directional && !(glm::length(v) > 0.0f))
        fail("--light zero direction: " + text);
      break;
    }
    case 2:
      if (!unit_colour(sylva::parse_background(text))) fail("--background: " + text);
      break;
    default:
      if (!unit_colour(sylva::parse_ground_color(text))) fail("--ground-color: " + text);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  sylva::fuzz::expect_input_error([&] { parse(data[0], text); });
  return 0;
}
