// Bounds-checked reading of glTF accessors from a tinygltf model: any component type
// (normalized integers mapped to [0, 1] / [-1, 1]), any byteStride, with every offset, count
// and stride checked against its bufferView and buffer before a byte is read, so hostile
// files end in InputError instead of out-of-range reads. Used by gltf_read.cpp only;
// header-only so it needs no build entry of its own.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {

class GltfAccessorReader {
 public:
  // `path` names the file in error messages.
  GltfAccessorReader(const tinygltf::Model& model, const std::string& path)
      : m_model(model), m_path(path) {}

  // count * components values; `what` (e.g. "POSITION") goes into error messages.
  // NaN or infinite values are an error.
  std::vector<float> floats(int index, int& components, const char* what) const {
    const tinygltf::Accessor& acc = accessor(index, what);
    components = tinygltf::GetNumComponentsInType(uint32_t(acc.type));
    const int csize = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    if (components <= 0 || csize <= 0) fail(index, what, "has an invalid type");
    const size_t elem = size_t(components) * size_t(csize);
    const unsigned char* base = data(acc, elem, index, what);
    std::vector<float> out(acc.count * size_t(components), 0.0f);
    if (!base) return out;  // glTF: an accessor without bufferView is all zeros
    const size_t stride = stride_of(acc, elem);
    for (size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * size_t(components) + size_t(c)] = component(
            base + i * stride + size_t(c) * size_t(csize), acc.componentType, acc.normalized);
    for (float v : out)
      if (!std::isfinite(v)) fail(index, what, "has NaN or infinite values");
    return out;
  }

  // Unsigned 8/16/32-bit scalars widened to 32 bits.
  std::vector<uint32_t> indices(int index) const {
    const tinygltf::Accessor& acc = accessor(index, "indices");
    const int ct = acc.componentType;
    if (acc.type != TINYGLTF_TYPE_SCALAR || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                             ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      fail(index, "indices", "must be unsigned 8/16/32-bit scalars");
    const size_t csize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(ct)));
    const unsigned char* base = data(acc, csize, index, "indices");
    std::vector<uint32_t> out(acc.count, 0u);
    if (!base) return out;
    const size_t stride = stride_of(acc, csize);
    for (size_t i = 0; i < acc.count; ++i) {
      const unsigned char* p = base + i * stride;
      if (csize == 1) {
        out[i] = *p;
      } else if (csize == 2) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        out[i] = v;
      } else {
        std::memcpy(&out[i], p, 4);
      }
    }
    return out;
  }

 private:
  // Accessors without a bufferView allocate zeros; this bounds what a hostile count costs.
  static constexpr size_t kMaxZeroCount = size_t(1) << 22;

  [[noreturn]] void fail(int index, const char* what, const std::string& msg) const {
    throw InputError(m_path, "accessor " + std::to_string(index) + " (" + what + ") " + msg);
  }

  const tinygltf::Accessor& accessor(int index, const char* what) const {
    if (index < 0 || size_t(index) >= m_model.accessors.size()) fail(index, what, "does not exist");
    const tinygltf::Accessor& acc = m_model.accessors[size_t(index)];
    if (acc.sparse.isSparse) fail(index, what, "is sparse; sparse accessors are not supported");
    return acc;
  }

  size_t stride_of(const tinygltf::Accessor& acc, size_t elem) const {
    const size_t s = m_model.bufferViews[size_t(acc.bufferView)].byteStride;
    return s == 0 ? elem : s;
  }

  // The first element's bytes, or null for an accessor without bufferView. All arithmetic
  // is 64-bit with each term bounded by the buffer size first, so nothing can wrap around.
  const unsigned char* data(const tinygltf::Accessor& acc, size_t elem, int index,
                            const char* what) const {
    if (acc.bufferView < 0) {
      if (acc.count > kMaxZeroCount) fail(index, what, "is too large");
      return nullptr;
    }
    if (size_t(acc.bufferView) >= m_model.bufferViews.size())
      fail(index, what, "refers to a missing bufferView");
    const tinygltf::BufferView& view = m_model.bufferViews[size_t(acc.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= m_model.buffers.size())
      fail(index, what, "has a bufferView that refers to a missing buffer");
    const std::vector<unsigned char>& buffer = m_model.buffers[size_t(view.buffer)].data;
    const size_t stride = view.byteStride == 0 ? elem : view.byteStride;
    if (stride < elem) fail(index, what, "has a byteStride smaller than one element");
    const uint64_t view_end = uint64_t(view.byteOffset) + uint64_t(view.byteLength);
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() ||
        view_end > buffer.size())
      fail(index, what, "has a bufferView that runs past the end of its buffer");
    if (acc.count > buffer.size() || acc.byteOffset > buffer.size())
      fail(index, what, "runs past the end of its bufferView");
    const uint64_t end = uint64_t(view.byteOffset) + acc.byteOffset +
                         (acc.count == 0 ? 0 : (acc.count - 1) * stride + elem);
    if (end > view_end) fail(index, what, "runs past the end of its bufferView");
    return buffer.data() + view.byteOffset + acc.byteOffset;
  }

  static float component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? *p / 255.0f : float(*p);
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = float(int8_t(*p));
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0f : float(v);
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0f, -1.0f) : float(v);
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return normalized ? float(v / 4294967295.0) : float(v);
      }
      default:
        return 0.0f;
    }
  }

  const tinygltf::Model& m_model;
  const std::string& m_path;
};

}  // namespace sylva
