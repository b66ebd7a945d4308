// Toon shading (Decaudin 1996, "Cartoon-looking rendering of 3D scenes"): the diffuse term
// N·L of a driving light is quantised into k flat bands, each a fixed multiple of the unlit
// base colour, with a separate shadow tone where the surface faces away from the key light
// (and, optionally, where a shadow map says the key light is blocked) and an optional flat
// specular highlight band.
//
// Reads:  "normal"   CV_32FC3 view-space normal (re-normalised here; background 0)
//         "albedo"   CV_8UC4 BGRA sRGB unlit base colour, alpha = coverage (gbuffer.h); the
//                    colour is taken as premultiplied by coverage in linear light, as the
//                    raster pass's SSAA down-sampling leaves it
//         "ka"       CV_32FC1 ambient coefficient in [0, 1]; optional, read only when
//                    toon.ka_weight > 0 (else the ka preprocessing is culled)
//         "position" CV_32FC3 view-space position; read only for point lights and cast
//                    shadows (toon_needs_position)
//         shadow     a ToonShadowMap from the key light; read only when toon.cast_shadows
// Writes: "toon"     CV_8UC4 BGRA sRGB, alpha = the albedo's coverage; background pixels
//                    (alpha 0) are the albedo's bytes unchanged.
// It never reads an ID buffer, so a toon-only graph never rasterises one.
//
// Shading, per covered pixel, all in linear light (sRGB is decoded first, encoded last):
//   s      = N·L of the key light ("key"), or the sum of every light's clamped N·L weighted by
//            its luminance relative to the brightest ("sum", clamped to 1; where no light
//            reaches, the largest N·L, so s < 0 still means shadow)
//   band b = number of thresholds t_j <= s                        (k bands, k-1 thresholds)
//   colour = albedo * tone[b] * mix(1, ka, ka_weight)
//            * (shadow * shadow_tint where s < 0 or the key light is blocked)
//   highlight (optional): where N·H of the key light >= specular_threshold on the lit side,
//            colour = mix(colour, key light colour, specular_strength)
// Light intensities only choose the key light and weight the sum: the band tones set the
// brightness, as a cartoon palette does. The view direction for the highlight is taken as
// view-space +Z (orthographic), which flat highlight bands do not reveal.
#pragma once

#include <glm/glm.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/gl/lights.h"
#include "core/graph/render_graph.h"
#include "core/params.h"

namespace sylva {

// toon.light: Key (default) = the brightest directional light drives the bands (else the
// brightest point light; no lights = a headlight along view +Z); Sum = all lights.
enum class ToonLight { Key, Sum };

struct ToonParams {
  // toon.bands: number of lit bands k; [2, 8]; default 3.
  int bands = 3;
  // toon.thresholds: N·L values where one band ends and the next begins (unitless N·L):
  // "even" (default) = j/k for j = 1..k-1, evenly over the lit side [0, 1]; or k-1 increasing
  // numbers in (-1, 1) separated by commas, e.g. "0.2,0.6". Negative thresholds put bands
  // on the shadow side (toon.shadow then darkens them).
  std::string thresholds = "even";
  // toon.tones: each band's brightness as a multiple of the base colour, darkest band first:
  // "auto" (default) = 0.55, 0.8, 1.0 interpolated piecewise linearly over k bands; or k
  // numbers in [0, 2] separated by commas.
  std::string tones = "auto";
  // toon.shadow: multiplier of the band tone where s < 0 or the key light is blocked; [0, 1];
  // default 0.6 (1 = no separate shadow tone).
  float shadow = 0.6f;
  // toon.shadow_tint: colour multiplying the shadow tone (linear RGB from "#RRGGBB");
  // default white = no tint.
  glm::vec3 shadow_tint{1.0f};
  // toon.ka_weight: how much the ambient coefficient darkens the bands, tone * mix(1, ka, w);
  // [0, 1]; default 0.5 (0 = ka is not read).
  float ka_weight = 0.5f;
  // toon.light: what drives the bands (ToonLight); default key.
  ToonLight light = ToonLight::Key;
  // toon.specular: a flat highlight band from the key light; default false.
  bool specular = false;
  // toon.specular_threshold: N·H (Blinn half vector) above which the highlight shows;
  // [0, 1]; default 0.97.
  float specular_threshold = 0.97f;
  // toon.specular_strength: mix from the band colour toward the key light's colour
  // (normalised to its brightest channel); [0, 1]; default 0.8.
  float specular_strength = 0.8f;
  // toon.cast_shadows: shadows cast by the key light, from a shadow map the style renders
  // from it (ToonShadowMap); default false.
  bool cast_shadows = false;
  // toon.shadow_bias: depth bias against self-shadowing, in shadow-map texels, scaled by the
  // slope (1 + tan of the light's incidence angle); [0, 8]; default 1.5.
  float shadow_bias = 1.5f;
  // toon.shadow_map_size: side of the square shadow map the style renders from the key light,
  // in pixels; [64, 8192]; default 2048 (a texel is then ~1/1000 of the scene's diameter).
  int shadow_map_size = 2048;
};

// A depth image rendered from the key light's camera, as the raster pass's depth target:
// linear depth along the light camera's -Z in scene units, 0 = nothing rendered, row 0 at
// the top. light_view maps world to light view space, light_proj light view space to clip
// space (orthographic or perspective).
struct ToonShadowMap {
  cv::Mat depth;  // CV_32FC1; empty = no shadow map
  glm::mat4 light_view{1.0f};
  glm::mat4 light_proj{1.0f};
};

struct ToonImages {
  cv::Mat normal;        // CV_32FC3, required
  cv::Mat albedo;        // CV_8UC4, required, same size
  cv::Mat ka;            // CV_32FC1 or empty (ka = 1)
  cv::Mat position;      // CV_32FC3 or empty; required when toon_needs_position()
  ToonShadowMap shadow;  // used when toon.cast_shadows
};

// Binds every field of `p` to its "toon.*" key. toon.thresholds and toon.tones are checked
// when set against the current toon.bands (set toon.bands first); validate_toon_params
// checks them again when the pass is built.
void bind_toon_params(ParamSet& set, ToonParams& p);

// Throws InputError naming the key (e.g. "toon.thresholds") for any value outside its range
// or a thresholds/tones list that does not fit toon.bands.
void validate_toon_params(const ToonParams& p);

// The resolved k-1 thresholds and k tones (validate first).
std::vector<float> toon_thresholds(const ToonParams& p);
std::vector<float> toon_tones(const ToonParams& p);

// Index into lights.lights of the key light (brightest directional by luminance, ties to the
// first; else the brightest point light), or -1 when there are none (a headlight along view
// +Z drives the bands). A style renders the shadow map from this light.
int toon_key_light(const Lighting& lights);

// Whether shading needs the view-space position image: a point light drives the bands, or
// toon.cast_shadows is set.
bool toon_needs_position(const Lighting& lights, const ToonParams& p);

// The shaded image in linear light, CV_32FC4 (B, G, R, coverage), colour premultiplied by
// coverage and not clamped (tones above 1 may exceed 1). view: world to view space, for
// lights that are not camera_fixed and for the shadow map.
cv::Mat toon_shade_linear(const ToonImages& in, const Lighting& lights, const glm::mat4& view,
                          const ToonParams& p);
// The same, encoded as CV_8UC4 BGRA sRGB; background pixels (albedo alpha 0) are copied.
cv::Mat toon_shade(const ToonImages& in, const Lighting& lights, const glm::mat4& view,
                   const ToonParams& p);

// Graph resource ids; -1 = not available. normal and albedo are required; ka is read only
// when p.ka_weight > 0; position only when toon_needs_position(); shadow (a resource holding
// a ToonShadowMap) only when p.cast_shadows, and then it must be given.
struct ToonResources {
  ImageHandle normal{}, albedo{}, ka{}, position{};
  Handle<ToonShadowMap> shadow{};
};

// Adds the pass "toon" writing the resource "toon" (returned). Validates `p` and `lights`
// now (InputError), so bad parameters fail before anything renders.
ImageHandle add_toon_pass(RenderGraph& graph, const ToonResources& res, const Lighting& lights,
                          const glm::mat4& view, const ToonParams& p);

}  // namespace sylva
