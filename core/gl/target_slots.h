// The raster's colour attachments, one slot per G-buffer target (kAllTargets order): their
// formats, the framebuffer memory a set of them takes, and reading them back into a GBuffer
// (SSAA averaged down, GL's bottom-up rows flipped). Reads the bound GL context; writes OpenCV
// images (core/gl/gbuffer.h).
#pragma once

#include <opencv2/core.hpp>

#include "core/gl/gbuffer.h"
#include "core/gl/gl_api.h"

namespace sylva {

inline constexpr int kSlots = 8;  // colour attachments, one per Target in kAllTargets order

// Attachment formats: colour is sRGB-encoded by the shader into plain RGBA8 (SSAA decodes
// it to average in linear light); normals, depth, position and ka are 32-bit float (llvmpipe
// truncates to half floats, which left normals ~0.1% short); ids are 32-bit unsigned.
struct SlotFormat {
  GLenum internal_format;
  int bytes;  // per sample
  GLenum read_format;
  GLenum read_type;
  int cv_type;
};

// Slot i's format (colour, normal, depth, position, id, ka, albedo, ao), i in [0, kSlots).
const SlotFormat& slot_format(int slot);

// Bytes of a width x height framebuffer with `targets` and the depth attachment.
double framebuffer_bytes(TargetMask targets, int width, int height);

// The `targets` of framebuffer `fbo` (width x height samples, `ssaa` per axis) read back at
// 1/ssaa of that size, top row first; the id target's samples too when `id_samples`.
GBuffer read_targets(GLuint fbo, int width, int height, TargetMask targets, int ssaa,
                     bool id_samples);

}  // namespace sylva
