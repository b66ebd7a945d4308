#include "core/gl/target_slots.h"

#include "core/error.h"
#include "core/gl/downsample.h"

namespace sylva {

namespace {

// Indexed by slot (kAllTargets order): colour, normal, depth, position, id, ka, albedo, ao.
constexpr SlotFormat kSlotFormats[kSlots] = {
    {GL_RGBA8, 4, GL_BGRA, GL_UNSIGNED_BYTE, CV_8UC4},
    {GL_RGBA32F, 16, GL_RGB, GL_FLOAT, CV_32FC3},
    {GL_R32F, 4, GL_RED, GL_FLOAT, CV_32FC1},
    {GL_RGBA32F, 16, GL_RGB, GL_FLOAT, CV_32FC3},
    {GL_R32UI, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, CV_32SC1},
    {GL_R32F, 4, GL_RED, GL_FLOAT, CV_32FC1},
    {GL_RGBA8, 4, GL_BGRA, GL_UNSIGNED_BYTE, CV_8UC4},
    {GL_R32F, 4, GL_RED, GL_FLOAT, CV_32FC1},
};
static_assert(kAllTargets[0] == Target::Color && kAllTargets[5] == Target::Ka &&
              kAllTargets[6] == Target::Albedo && kAllTargets[7] == Target::Ao);

cv::Mat read_slot(int slot, int width, int height) {
  const SlotFormat& f = kSlotFormats[slot];
  cv::Mat m(height, width, f.cv_type);
  glReadBuffer(GL_COLOR_ATTACHMENT0 + slot);
  glReadPixels(0, 0, width, height, f.read_format, f.read_type, m.data);
  return m;
}

// Non-zero where a sample is geometry (depth attachment written), at SSAA resolution.
cv::Mat read_coverage(int width, int height) {
  cv::Mat depth(height, width, CV_32FC1);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data);
  cv::Mat coverage;
  cv::compare(depth, 1.0f, coverage, cv::CMP_LT);
  return coverage;
}

}  // namespace

const SlotFormat& slot_format(int slot) {
  SYLVA_CHECK(slot >= 0 && slot < kSlots, "slot_format: no such slot");
  return kSlotFormats[slot];
}

double framebuffer_bytes(TargetMask targets, int width, int height) {
  double bytes = 4.0;  // the depth attachment
  for (int i = 0; i < kSlots; ++i) {
    if (has(targets, kAllTargets[i])) bytes += kSlotFormats[i].bytes;
  }
  return bytes * static_cast<double>(width) * height;
}

GBuffer read_targets(GLuint fbo, int width, int height, TargetMask targets, int ssaa,
                     bool id_samples) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  GBuffer out;
  out.targets = targets;
  const TargetMask averaged =
      Target::Normal | Target::Depth | Target::Position | Target::Ka | Target::Ao;
  cv::Mat coverage;
  if (ssaa > 1 && (targets & averaged) != 0) coverage = read_coverage(width, height);
  for (int i = 0; i < kSlots; ++i) {
    const Target t = kAllTargets[i];
    if (!has(targets, t)) continue;
    cv::Mat m = read_slot(i, width, height);
    if (t == Target::Color || t == Target::Albedo) {
      m = downsample_color(m, ssaa);
    } else if (t == Target::Id) {
      if (id_samples) cv::flip(m, out.id_samples, 0);
      m = downsample_id(m, ssaa);
    } else if (ssaa > 1) {
      m = downsample_covered(m, coverage, ssaa, t == Target::Normal);
    }
    cv::flip(m, m, 0);  // GL's row 0 is the bottom; in place (cv::flip swaps row pairs)
    target_image(out, t) = m;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return out;
}

}  // namespace sylva
