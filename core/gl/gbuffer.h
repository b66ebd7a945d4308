// The G-buffer targets the raster pass can produce, and the images it returns. All images
// are width x height (after SSAA down-sampling), row 0 at the top.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

namespace sylva {

enum class Target : uint32_t {
  Color = 1u << 0,     // CV_8UC4 BGRA, sRGB; alpha = coverage (0 background)
  Normal = 1u << 1,    // CV_32FC3 view-space unit normal (x, y, z), background 0
  Depth = 1u << 2,     // CV_32FC1 linear view depth (positive distance along -Z), bg 0
  Position = 1u << 3,  // CV_32FC3 view-space position, background 0
  Id = 1u << 4,        // CV_32SC1 id (see IdKind), background 0
  Ka = 1u << 5,        // CV_32FC1 ambient coefficient in [0, 1], background 0
  Albedo = 1u << 6,    // CV_8UC4 BGRA, sRGB: unlit base colour (material x texture x vertex
                       // colour); alpha = coverage, background 0
  Ao = 1u << 7,        // CV_32FC1 ambient visibility in [0, 1] (RasterRequest::ao), bg 0
};
using TargetMask = uint32_t;
constexpr TargetMask operator|(Target a, Target b) {
  return static_cast<TargetMask>(a) | static_cast<TargetMask>(b);
}
constexpr TargetMask operator|(TargetMask a, Target b) {
  return a | static_cast<TargetMask>(b);
}
constexpr bool has(TargetMask m, Target t) {
  return (m & static_cast<TargetMask>(t)) != 0;
}
const char* target_name(Target t);  // "color", "normal", ...
int target_count(TargetMask m);

// Every target, in bit order (also the raster pass's colour-attachment slot order).
inline constexpr Target kAllTargets[] = {Target::Color,    Target::Normal, Target::Depth,
                                         Target::Position, Target::Id,     Target::Ka,
                                         Target::Albedo,   Target::Ao};
inline constexpr TargetMask kAllTargetsMask = (1u << 8) - 1u;

// Object = mesh index + 1; Material = the mesh's material index + 1, or the number of
// materials + 1 for meshes without one (the default grey).
enum class IdKind { Primitive, Cluster, Object, Material };

struct GBuffer {
  TargetMask targets = 0;
  cv::Mat color, normal, depth, position, id, ka, albedo, ao;
  // The id target's samples before down-sampling (ssaa x the size, rows top to bottom), when
  // RasterRequest::id_samples asks for them; at ssaa 1 the id image itself.
  cv::Mat id_samples;
};

// The image of one target (empty when it was not rendered).
cv::Mat& target_image(GBuffer& buffer, Target t);
const cv::Mat& target_image(const GBuffer& buffer, Target t);

}  // namespace sylva
