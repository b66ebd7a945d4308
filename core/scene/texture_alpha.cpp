#include "core/scene/texture_alpha.h"

#include <algorithm>
#include <cmath>

namespace sylva {

bool is_cutout(const Scene& scene, const Material& material) {
  return material.alpha_mode != AlphaMode::Opaque && material.base_color_texture >= 0 &&
         size_t(material.base_color_texture) < scene.textures.size();
}

bool drawn_at(const Scene& scene, const Material& material, glm::vec2 uv) {
  if (!is_cutout(scene, material)) return true;
  const Texture& t = scene.textures[size_t(material.base_color_texture)];
  if (t.width <= 0 || t.height <= 0) return true;
  const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
  const int x = std::clamp(int(u * float(t.width)), 0, t.width - 1);
  const int y = std::clamp(int(v * float(t.height)), 0, t.height - 1);
  const size_t at = 4 * (size_t(y) * size_t(t.width) + size_t(x)) + 3;
  const float a = at < t.rgba.size() ? t.rgba[at] / 255.0f : 1.0f;
  const float cutoff = material.alpha_mode == AlphaMode::Mask ? material.alpha_cutoff : 0.5f;
  return a * material.base_color.a >= cutoff;
}

}  // namespace sylva
