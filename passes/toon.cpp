#include "passes/toon.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <opencv2/core/utility.hpp>

#include "core/color.h"
#include "core/error.h"
#include "passes/pass_common.h"

namespace sylva {

namespace {

constexpr int kMinBands = 2, kMaxBands = 8;
constexpr float kMaxTone = 2.0f, kMaxBias = 8.0f;

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

const std::array<float, 256>& srgb_decode_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i)
      t[i] = srgb_to_linear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// Linear value where the 8-bit sRGB code steps from i to i + 1: encoding is a binary search,
// exact to the rounding of lround(linear_to_srgb(v) * 255) and much cheaper than pow().
const std::array<float, 255>& srgb_encode_steps() {
  static const std::array<float, 255> steps = [] {
    std::array<float, 255> s{};
    for (int i = 0; i < 255; ++i)
      s[i] = srgb_to_linear((float(i) + 0.5f) / 255.0f);
    return s;
  }();
  return steps;
}

uint8_t srgb_encode(float v) {
  const auto& s = srgb_encode_steps();
  if (!(v > 0.0f)) return 0;  // also NaN
  return uint8_t(std::upper_bound(s.begin(), s.end(), v) - s.begin());
}

// "a, b, c" -> numbers; false on an empty item, trailing text or a non-finite value.
bool parse_numbers(const std::string& text, std::vector<double>& out) {
  out.clear();
  size_t begin = 0;
  while (true) {
    size_t end = text.find(',', begin);
    if (end == std::string::npos) end = text.size();
    size_t a = begin, b = end;
    while (a < b && (text[a] == ' ' || text[a] == '\t'))
      ++a;
    while (b > a && (text[b - 1] == ' ' || text[b - 1] == '\t'))
      --b;
    if (a == b) return false;
    double v = 0.0;
    const char* first = text.data() + a;
    const char* last = text.data() + b;
    if (*first == '+') ++first;  // from_chars rejects a leading '+'
    auto [p, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || p != last || !std::isfinite(v)) return false;
    out.push_back(v);
    if (end == text.size()) return true;
    begin = end + 1;
  }
}

void check_thresholds(const std::string& text, const std::string& where, int bands) {
  if (text == "even") return;
  const std::string allowed = "give \"even\" or toon.bands - 1 = " + std::to_string(bands - 1) +
                              " increasing numbers in (-1, 1) separated by commas, e.g. " +
                              "\"0.2,0.6\" (set toon.bands first)";
  auto fail = [&](const std::string& why) {
    throw InputError(where, "\"" + text + "\" " + why + "; " + allowed);
  };
  std::vector<double> v;
  if (!parse_numbers(text, v)) fail("is not a list of numbers");
  if (int(v.size()) != bands - 1) fail("has " + std::to_string(v.size()) + " values");
  for (size_t i = 0; i < v.size(); ++i) {
    if (!(v[i] > -1.0 && v[i] < 1.0)) fail("has a value outside (-1, 1)");
    if (i > 0 && !(v[i] > v[i - 1])) fail("is not increasing");
  }
}

void check_tones(const std::string& text, const std::string& where, int bands) {
  if (text == "auto") return;
  const std::string allowed = "give \"auto\" or toon.bands = " + std::to_string(bands) +
                              " numbers in [0, 2] separated by commas, darkest band first, " +
                              "e.g. \"0.5,0.8,1\" (set toon.bands first)";
  auto fail = [&](const std::string& why) {
    throw InputError(where, "\"" + text + "\" " + why + "; " + allowed);
  };
  std::vector<double> v;
  if (!parse_numbers(text, v)) fail("is not a list of numbers");
  if (int(v.size()) != bands) fail("has " + std::to_string(v.size()) + " values");
  for (double t : v)
    if (!(t >= 0.0 && t <= kMaxTone)) fail("has a value outside [0, 2]");
}

void check_range(const char* key, float v, float lo, float hi) {
  if (!(v >= lo && v <= hi))
    throw InputError(key, std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                              std::to_string(hi) + "]");
}

// A light as the pass uses it: view-space direction toward the light, or view-space
// position for a point light; weight = share of the band driver.
struct DriveLight {
  glm::vec3 v{0.0f, 0.0f, 1.0f};
  bool point = false;
  float weight = 1.0f;
  bool key = false;
};

DriveLight to_view(const Light& l, const glm::mat4& view) {
  DriveLight d;
  d.point = l.type == Light::Type::Point;
  d.v = light_in_view(l, view);
  return d;
}

glm::vec3 direction_at(const DriveLight& l, const glm::vec3& pos, const glm::vec3& n) {
  if (!l.point) return l.v;
  const glm::vec3 to = l.v - pos;
  const float len = glm::length(to);
  return len > 1e-12f ? to / len : n;
}

// Whether the key light is blocked at view-space `pos` according to the shadow map; nl is the
// key light's N·L (>= 0) for the slope-scaled bias.
struct ShadowLookup {
  const ToonShadowMap* map = nullptr;
  glm::mat4 view_to_light{1.0f};  // light_view * inverse(view)
  bool perspective = false;
  float texel_scale = 0.0f;  // texel size in scene units at depth 1 (perspective) or anywhere
  float bias_texels = 0.0f;

  bool blocked(const glm::vec3& pos, float nl) const {
    const glm::vec4 lv = view_to_light * glm::vec4(pos, 1.0f);
    const glm::vec4 clip = map->light_proj * lv;
    if (!(clip.w > 0.0f)) return false;
    const float nx = clip.x / clip.w, ny = clip.y / clip.w;
    if (!(nx >= -1.0f && nx <= 1.0f && ny >= -1.0f && ny <= 1.0f)) return false;
    const cv::Mat& d = map->depth;
    const int col = std::clamp(int(std::floor((nx * 0.5f + 0.5f) * float(d.cols))), 0, d.cols - 1);
    const int row = std::clamp(int(std::floor((0.5f - ny * 0.5f) * float(d.rows))), 0, d.rows - 1);
    const float stored = d.at<float>(row, col);
    if (!(stored > 0.0f)) return false;  // nothing rendered there
    const float depth = -lv.z;
    const float texel = texel_scale * (perspective ? depth : 1.0f);
    const float slope = nl > 0.1f ? std::min(std::sqrt(1.0f - nl * nl) / nl, 10.0f) : 10.0f;
    return depth - bias_texels * texel * (1.0f + slope) > stored;
  }
};

}  // namespace

void validate_toon_params(const ToonParams& p) {
  if (!(p.bands >= kMinBands && p.bands <= kMaxBands))
    throw InputError("toon.bands", std::to_string(p.bands) + " is outside [2, 8]");
  check_thresholds(p.thresholds, "toon.thresholds", p.bands);
  check_tones(p.tones, "toon.tones", p.bands);
  check_range("toon.shadow", p.shadow, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c)
    check_range("toon.shadow_tint", p.shadow_tint[c], 0.0f, 1.0f);
  check_range("toon.ka_weight", p.ka_weight, 0.0f, 1.0f);
  if (p.light != ToonLight::Key && p.light != ToonLight::Sum)
    throw InputError("toon.light", "is not one of key, sum");
  check_range("toon.specular_threshold", p.specular_threshold, 0.0f, 1.0f);
  check_range("toon.specular_strength", p.specular_strength, 0.0f, 1.0f);
  check_range("toon.shadow_bias", p.shadow_bias, 0.0f, kMaxBias);
  if (!(p.shadow_map_size >= 64 && p.shadow_map_size <= 8192))
    throw InputError("toon.shadow_map_size",
                     std::to_string(p.shadow_map_size) + " is outside [64, 8192] px");
}

std::vector<float> toon_thresholds(const ToonParams& p) {
  std::vector<float> t;
  if (p.thresholds == "even") {
    for (int j = 1; j < p.bands; ++j)
      t.push_back(float(j) / float(p.bands));
    return t;
  }
  std::vector<double> v;
  SYLVA_CHECK(parse_numbers(p.thresholds, v), "toon.thresholds not validated");
  for (double x : v)
    t.push_back(float(x));
  return t;
}

std::vector<float> toon_tones(const ToonParams& p) {
  std::vector<float> t;
  if (p.tones == "auto") {
    // Piecewise linear through 0.55 (darkest), 0.8 (middle), 1.0 (brightest): k = 3 gives
    // exactly these, other k sample the same curve.
    for (int j = 0; j < p.bands; ++j) {
      const float x = float(j) / float(p.bands - 1);
      t.push_back(x <= 0.5f ? 0.55f + 0.5f * x : 0.8f + 0.4f * (x - 0.5f));
    }
    return t;
  }
  std::vector<double> v;
  SYLVA_CHECK(parse_numbers(p.tones, v), "toon.tones not validated");
  for (double x : v)
    t.push_back(float(x));
  return t;
}

int toon_key_light(const Lighting& lights) {
  int best = -1;
  float best_lum = -1.0f;
  for (int pass = 0; pass < 2 && best < 0; ++pass) {  // directional first, then point lights
    const Light::Type type = pass == 0 ? Light::Type::Directional : Light::Type::Point;
    for (size_t i = 0; i < lights.lights.size(); ++i) {
      const Light& l = lights.lights[i];
      if (l.type != type) continue;
      const float lum = luminance(l.color);
      if (lum > best_lum) {
        best_lum = lum;
        best = int(i);
      }
    }
  }
  return best;
}

bool toon_needs_position(const Lighting& lights, const ToonParams& p) {
  if (p.cast_shadows) return true;
  if (p.light == ToonLight::Sum) {
    for (const Light& l : lights.lights)
      if (l.type == Light::Type::Point) return true;
    return false;
  }
  const int key = toon_key_light(lights);
  return key >= 0 && lights.lights[size_t(key)].type == Light::Type::Point;
}

void bind_toon_params(ParamSet& set, ToonParams& p) {
  const int* bands = &p.bands;
  set.add_int("toon.bands", p.bands, kMinBands, kMaxBands, "bands",
              "number of flat lit bands (Decaudin 1996)");
  set.add_text(
      "toon.thresholds", p.thresholds,
      [bands](const std::string& text, const std::string& where) {
        check_thresholds(text, where, *bands);
      },
      "\"even\" (j/k on the lit side) or toon.bands - 1 increasing N·L values in (-1, 1), "
      "e.g. \"0.2,0.6\"",
      "N·L values where one band ends and the next begins");
  set.add_text(
      "toon.tones", p.tones,
      [bands](const std::string& text, const std::string& where) {
        check_tones(text, where, *bands);
      },
      "\"auto\" (0.55, 0.8, 1.0 interpolated) or toon.bands numbers in [0, 2], darkest first",
      "each band's brightness as a multiple of the base colour");
  set.add_float("toon.shadow", p.shadow, 0.0, 1.0, "x band tone",
                "shadow-side (N·L < 0 or blocked) brightness as a multiple of the band tone");
  set.add_color("toon.shadow_tint", p.shadow_tint, "colour multiplying the shadow tone");
  set.add_float("toon.ka_weight", p.ka_weight, 0.0, 1.0, "",
                "how much the ambient coefficient darkens the bands: tone * mix(1, ka, w)");
  set.add_choice("toon.light", p.light, {{"key", ToonLight::Key}, {"sum", ToonLight::Sum}},
                 "what drives the bands: the brightest directional light, or all lights");
  set.add_bool("toon.specular", p.specular, "flat highlight band from the key light");
  set.add_float("toon.specular_threshold", p.specular_threshold, 0.0, 1.0, "N·H",
                "half-vector cosine above which the highlight shows");
  set.add_float("toon.specular_strength", p.specular_strength, 0.0, 1.0, "",
                "mix from the band colour toward the key light's colour in the highlight");
  set.add_bool("toon.cast_shadows", p.cast_shadows,
               "shadows cast by the key light (from a shadow map)");
  set.add_float("toon.shadow_bias", p.shadow_bias, 0.0, kMaxBias, "shadow-map texels",
                "depth bias against self-shadowing, scaled by the slope");
  set.add_int("toon.shadow_map_size", p.shadow_map_size, 64, 8192, "px",
              "side of the square shadow map rendered from the key light");
}

cv::Mat toon_shade_linear(const ToonImages& in, const Lighting& lights, const glm::mat4& view,
                          const ToonParams& p) {
  validate_toon_params(p);
  validate_lighting(lights);
  expect_image(in.normal, CV_32FC3, cv::Size(), "normal");
  const cv::Size size = in.normal.size();
  expect_image(in.albedo, CV_8UC4, size, "albedo");
  const bool use_ka = !in.ka.empty() && p.ka_weight > 0.0f;
  if (use_ka) expect_image(in.ka, CV_32FC1, size, "ka");
  const bool use_shadow = p.cast_shadows && !in.shadow.depth.empty();
  if (use_shadow) expect_image(in.shadow.depth, CV_32FC1, cv::Size(), "shadow map");
  const bool need_pos = use_shadow || toon_needs_position(lights, p);
  SYLVA_CHECK(!need_pos || !in.position.empty(),
              "toon: point lights and cast shadows need the position image");
  if (need_pos) expect_image(in.position, CV_32FC3, size, "position");

  // The lights that drive the bands, in view space.
  const int key = toon_key_light(lights);
  std::vector<DriveLight> drive;
  DriveLight key_light;  // headlight when there are no lights
  glm::vec3 highlight(1.0f);
  if (key >= 0) {
    const Light& k = lights.lights[size_t(key)];
    key_light = to_view(k, view);
    const float m = std::max({k.color.r, k.color.g, k.color.b});
    if (m > 0.0f) highlight = k.color / m;
  }
  key_light.key = true;
  if (p.light == ToonLight::Sum && !lights.lights.empty()) {
    float max_lum = 0.0f;
    for (const Light& l : lights.lights)
      max_lum = std::max(max_lum, luminance(l.color));
    for (size_t i = 0; i < lights.lights.size(); ++i) {
      const float lum = luminance(lights.lights[i].color);
      if (max_lum > 0.0f && !(lum > 0.0f)) continue;  // a black light lights nothing
      DriveLight d = to_view(lights.lights[i], view);
      d.weight = max_lum > 0.0f ? lum / max_lum : 1.0f;
      d.key = int(i) == key;
      drive.push_back(d);
    }
  } else {
    drive.push_back(key_light);
  }

  ShadowLookup shadow;
  if (use_shadow) {
    shadow.map = &in.shadow;
    shadow.view_to_light = in.shadow.light_view * glm::inverse(view);
    shadow.perspective = in.shadow.light_proj[3][3] == 0.0f;
    const float sx = std::abs(in.shadow.light_proj[0][0]);
    shadow.texel_scale = sx > 0.0f ? 2.0f / (sx * float(in.shadow.depth.cols)) : 0.0f;
    shadow.bias_texels = p.shadow_bias;
  }

  const std::vector<float> thresholds = toon_thresholds(p);
  const std::vector<float> tones = toon_tones(p);
  const int shadow_band_cap =  // the band a blocked pixel keeps: the one just below N·L = 0
      int(std::count_if(thresholds.begin(), thresholds.end(), [](float t) { return t < 0.0f; }));
  const glm::vec3 shadow_mul = p.shadow * p.shadow_tint;
  const auto& decode = srgb_decode_table();
  const glm::vec3 view_dir(0.0f, 0.0f, 1.0f);

  cv::Mat out(size, CV_32FC4);
  cv::parallel_for_(cv::Range(0, size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec3f* nrow = in.normal.ptr<cv::Vec3f>(y);
      const cv::Vec4b* arow = in.albedo.ptr<cv::Vec4b>(y);
      const float* krow = use_ka ? in.ka.ptr<float>(y) : nullptr;
      const cv::Vec3f* prow = need_pos ? in.position.ptr<cv::Vec3f>(y) : nullptr;
      cv::Vec4f* orow = out.ptr<cv::Vec4f>(y);
      for (int x = 0; x < size.width; ++x) {
        const cv::Vec4b a = arow[x];
        const float coverage = float(a[3]) / 255.0f;
        const glm::vec3 base(decode[a[2]], decode[a[1]], decode[a[0]]);  // linear RGB
        if (a[3] == 0) {
          orow[x] = cv::Vec4f(base.b, base.g, base.r, 0.0f);
          continue;
        }
        glm::vec3 n(nrow[x][0], nrow[x][1], nrow[x][2]);
        const float len = glm::length(n);
        n = len > 1e-12f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
        const glm::vec3 pos = prow ? glm::vec3(prow[x][0], prow[x][1], prow[x][2]) : glm::vec3(0);

        // Band driver s (header comment): lit where some driving light has N·L >= 0 and,
        // for the key light, the shadow map does not block it.
        const glm::vec3 key_dir = direction_at(key_light, pos, n);
        const float key_nl = glm::dot(n, key_dir);
        const bool key_lit = key_nl >= 0.0f && !(use_shadow && shadow.blocked(pos, key_nl));
        float acc = 0.0f, best_negative = -std::numeric_limits<float>::infinity();
        bool lit = false;
        for (const DriveLight& l : drive) {
          const float nl = l.key ? key_nl : glm::dot(n, direction_at(l, pos, n));
          if (l.key ? key_lit : nl >= 0.0f) {
            lit = true;
            acc += l.weight * nl;
          } else {
            best_negative = std::max(best_negative, std::min(nl, 0.0f));
          }
        }
        const float s = lit ? std::min(acc, 1.0f) : best_negative;
        int band =
            int(std::upper_bound(thresholds.begin(), thresholds.end(), s) - thresholds.begin());
        if (!lit) band = std::min(band, shadow_band_cap);

        const float k = krow ? (krow[x] >= 0.0f ? std::min(krow[x], 1.0f) : 0.0f) : 1.0f;
        glm::vec3 c = base * (tones[size_t(band)] * (1.0f + p.ka_weight * (k - 1.0f)));
        if (!lit) c *= shadow_mul;
        if (p.specular && key_lit) {
          const glm::vec3 h = key_dir + view_dir;
          const float h_len = glm::length(h);
          if (h_len > 1e-6f && glm::dot(n, h / h_len) >= p.specular_threshold)
            c = c + p.specular_strength * (highlight * coverage - c);  // premultiplied
        }
        orow[x] = cv::Vec4f(c.b, c.g, c.r, coverage);
      }
    }
  });
  return out;
}

cv::Mat toon_shade(const ToonImages& in, const Lighting& lights, const glm::mat4& view,
                   const ToonParams& p) {
  const cv::Mat lin = toon_shade_linear(in, lights, view, p);
  cv::Mat out(lin.size(), CV_8UC4);
  cv::parallel_for_(cv::Range(0, lin.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      const cv::Vec4f* l = lin.ptr<cv::Vec4f>(y);
      const cv::Vec4b* a = in.albedo.ptr<cv::Vec4b>(y);
      cv::Vec4b* o = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < lin.cols; ++x) {
        if (a[x][3] == 0) {
          o[x] = a[x];  // background untouched
          continue;
        }
        o[x] = cv::Vec4b(srgb_encode(l[x][0]), srgb_encode(l[x][1]), srgb_encode(l[x][2]), a[x][3]);
      }
    }
  });
  return out;
}

ImageHandle add_toon_pass(RenderGraph& graph, const ToonResources& res, const Lighting& lights,
                          const glm::mat4& view, const ToonParams& p) {
  validate_toon_params(p);
  validate_lighting(lights);
  SYLVA_CHECK(res.normal.valid() && res.albedo.valid(), "toon pass needs the normal and albedo");
  const bool use_ka = res.ka.valid() && p.ka_weight > 0.0f;
  const bool need_pos = toon_needs_position(lights, p);
  SYLVA_CHECK(!need_pos || res.position.valid(),
              "toon pass: point lights and toon.cast_shadows need the position resource");
  SYLVA_CHECK(!p.cast_shadows || res.shadow.valid(),
              "toon pass: toon.cast_shadows needs a shadow-map resource");
  std::vector<ResourceRef> reads = {res.normal, res.albedo};
  if (use_ka) reads.push_back(res.ka);
  if (need_pos) reads.push_back(res.position);
  if (p.cast_shadows) reads.push_back(res.shadow);
  const auto out = graph.resource<cv::Mat>("toon");
  graph.add_pass("toon", reads, {out},
                 [res, lights, view, p, use_ka, need_pos, out](PassContext& ctx) {
                   ToonImages in;
                   in.normal = ctx.read<cv::Mat>(res.normal);
                   in.albedo = ctx.read<cv::Mat>(res.albedo);
                   if (use_ka) in.ka = ctx.read<cv::Mat>(res.ka);
                   if (need_pos) in.position = ctx.read<cv::Mat>(res.position);
                   if (p.cast_shadows) in.shadow = ctx.read<ToonShadowMap>(res.shadow);
                   ctx.write(out, toon_shade(in, lights, view, p));
                 });
  return out;
}

}  // namespace sylva
