#include "core/gl/gbuffer.h"

#include <bit>

#include "core/error.h"

namespace sylva {

const char* target_name(Target t) {
  switch (t) {
    case Target::Color:
      return "color";
    case Target::Normal:
      return "normal";
    case Target::Depth:
      return "depth";
    case Target::Position:
      return "position";
    case Target::Id:
      return "id";
    case Target::Ka:
      return "ka";
    case Target::Albedo:
      return "albedo";
    case Target::Ao:
      return "ao";
  }
  return "unknown";
}

int target_count(TargetMask m) {
  return std::popcount(m & kAllTargetsMask);
}

cv::Mat& target_image(GBuffer& buffer, Target t) {
  switch (t) {
    case Target::Color:
      return buffer.color;
    case Target::Normal:
      return buffer.normal;
    case Target::Depth:
      return buffer.depth;
    case Target::Position:
      return buffer.position;
    case Target::Id:
      return buffer.id;
    case Target::Ka:
      return buffer.ka;
    case Target::Albedo:
      return buffer.albedo;
    case Target::Ao:
      return buffer.ao;
  }
  SYLVA_CHECK(false, "unknown target");
}

const cv::Mat& target_image(const GBuffer& buffer, Target t) {
  return target_image(const_cast<GBuffer&>(buffer), t);
}

}  // namespace sylva
