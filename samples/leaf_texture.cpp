#include "samples/leaf_texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/error.h"

namespace sylva {

namespace {

constexpr float kPi = 3.14159265358979f;

struct Rgb {
  float r, g, b;  // sRGB, 0..255
};

Rgb mix(const Rgb& a, const Rgb& b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Small deterministic per-texel noise in [-1, 1] (integer hash, no RNG state).
float texel_noise(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 374761393u + static_cast<uint32_t>(y) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  h ^= h >> 16;
  return static_cast<float>(h & 0xffff) / 32767.5f - 1.0f;
}

uint8_t to_byte(float v) {
  return static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

// Blade outline in physical leaf coordinates: x across (0 = midrib), y along (0 = petiole
// end, 1 = tip). Returns the half-width of the blade at y (0 outside the blade).
struct Outline {
  float blade_start;  // y where the blade begins (petiole below)
  float blade_end;    // y of the tip
  float half_width;   // maximum half-width
  float base_exp;     // roundness of the base
  float tip_exp;      // pointedness of the tip
  float petiole;      // petiole half-width

  float blade_s(float y) const { return (y - blade_start) / (blade_end - blade_start); }
  float width_at(float y) const {
    float s = blade_s(y);
    if (s <= 0.0f || s >= 1.0f) return 0.0f;
    // Normalise s^a (1-s)^b to peak 1 at s = a / (a + b).
    float peak_s = base_exp / (base_exp + tip_exp);
    float peak = std::pow(peak_s, base_exp) * std::pow(1.0f - peak_s, tip_exp);
    return half_width * std::pow(s, base_exp) * std::pow(1.0f - s, tip_exp) / peak;
  }
  bool inside(float x, float y) const {
    if (std::fabs(x) < width_at(y)) return true;
    return y >= 0.0f && y <= blade_start + 0.03f && std::fabs(x) < petiole;
  }
};

Outline outline_for(LeafTextureKind kind) {
  if (kind == LeafTextureKind::Needle) return {0.02f, 0.99f, 0.046f, 0.25f, 0.45f, 0.0f};
  return {0.10f, 0.98f, 0.27f, 0.55f, 0.85f, 0.012f};
}

Rgb broadleaf_color(const Outline& o, float x, float y, float noise) {
  const Rgb base{52, 104, 32}, tip{86, 138, 44}, rib{150, 178, 82}, vein{104, 148, 56};
  const Rgb stalk{96, 118, 48};
  if (y < o.blade_start) return stalk;
  float s = std::clamp(o.blade_s(y), 0.0f, 1.0f);
  float hw = std::max(o.width_at(y), 1e-3f);
  float ax = std::min(std::fabs(x), hw);
  Rgb c = mix(base, tip, 0.8f * s);
  c = mix(c, Rgb{120, 150, 50}, 0.35f * smoothstep(0.7f, 1.0f, ax / hw));  // lighter margin
  // Secondary veins leave the midrib towards the tip: lines s = s0 + k * |x|.
  float phase = (s - 0.45f * ax / o.half_width) * 8.0f;
  float dist = std::fabs(phase - std::round(phase)) / 8.0f * (o.blade_end - o.blade_start);
  float vein_w = 0.006f * (1.0f - 0.6f * ax / hw);
  float fade = (1.0f - smoothstep(0.6f, 1.0f, ax / hw)) * smoothstep(0.02f, 0.1f, s) *
               (1.0f - smoothstep(0.85f, 0.97f, s)) * (phase > 0.5f ? 1.0f : 0.0f);
  c = mix(c, vein, 0.7f * fade * (1.0f - smoothstep(0.3f * vein_w, vein_w, dist)));
  float rib_w = 0.011f * (1.0f - 0.8f * s) + 0.002f;
  c = mix(c, rib, 1.0f - smoothstep(0.5f * rib_w, rib_w, ax));
  return mix(c, Rgb{0, 0, 0}, 0.03f * noise);
}

Rgb needle_color(const Outline& o, float x, float y, float noise) {
  const Rgb base{28, 70, 34}, tip{52, 98, 44}, line{70, 112, 62};
  float s = std::clamp(o.blade_s(y), 0.0f, 1.0f);
  float hw = std::max(o.width_at(y), 1e-3f);
  Rgb c = mix(base, tip, s);
  c = mix(c, line, 0.6f * (1.0f - smoothstep(0.15f * hw, 0.4f * hw, std::fabs(x))));
  return mix(c, Rgb{0, 0, 0}, 0.03f * noise);
}

}  // namespace

float leaf_quad_aspect(LeafTextureKind kind) {
  return kind == LeafTextureKind::Needle ? 0.1f : 0.6f;
}

Texture make_leaf_texture(LeafTextureKind kind, int height) {
  SYLVA_CHECK(height >= 16 && height <= 1024, "leaf texture height out of range");
  const bool needle = kind == LeafTextureKind::Needle;
  const Outline o = outline_for(kind);
  const float aspect = leaf_quad_aspect(kind);
  Texture tex;
  tex.name = needle ? "needle" : "leaf";
  tex.height = height;
  tex.width = needle ? std::max(4, height / 4) : height;
  tex.rgba.resize(static_cast<size_t>(tex.width) * tex.height * 4);
  constexpr int kSub = 4;  // supersamples per axis for the alpha edge
  for (int py = 0; py < tex.height; ++py) {
    for (int px = 0; px < tex.width; ++px) {
      int covered = 0;
      for (int sy = 0; sy < kSub; ++sy) {
        for (int sx = 0; sx < kSub; ++sx) {
          float u = (px + (sx + 0.5f) / kSub) / tex.width;
          float v = (py + (sy + 0.5f) / kSub) / tex.height;
          covered += o.inside((u - 0.5f) * aspect, 1.0f - v) ? 1 : 0;
        }
      }
      float x = ((px + 0.5f) / tex.width - 0.5f) * aspect;
      float y = 1.0f - (py + 0.5f) / tex.height;
      float noise = texel_noise(px, py);
      Rgb c = needle ? needle_color(o, x, y, noise) : broadleaf_color(o, x, y, noise);
      uint8_t* p = &tex.rgba[(static_cast<size_t>(py) * tex.width + px) * 4];
      p[0] = to_byte(c.r);
      p[1] = to_byte(c.g);
      p[2] = to_byte(c.b);
      p[3] = to_byte(255.0f * covered / (kSub * kSub));
    }
  }
  return tex;
}

Texture make_bark_texture(int size) {
  SYLVA_CHECK(size >= 8 && size <= 1024, "bark texture size out of range");
  Texture tex;
  tex.name = "bark";
  tex.width = tex.height = size;
  tex.rgba.resize(static_cast<size_t>(size) * size * 4);
  for (int py = 0; py < size; ++py) {
    for (int px = 0; px < size; ++px) {
      float u = (px + 0.5f) / size, v = (py + 0.5f) / size;
      // Integer frequencies in u and v keep the pattern seamless when tiled.
      float f = 0.55f * std::sin(2 * kPi * (4 * u + 0.25f * std::sin(2 * kPi * v))) +
                0.30f * std::sin(2 * kPi * (9 * u + 0.35f * std::sin(2 * kPi * 2 * v))) +
                0.15f * texel_noise(px, py);
      float g = 212.0f + 40.0f * f;
      uint8_t* p = &tex.rgba[(static_cast<size_t>(py) * size + px) * 4];
      p[0] = p[1] = p[2] = to_byte(g);
      p[3] = 255;
    }
  }
  return tex;
}

}  // namespace sylva
