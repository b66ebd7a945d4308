// The binary glTF (.glb) container: a 12-byte header, a JSON chunk and an optional BIN chunk,
// each 4-byte aligned (glTF 2.0 §4.4). Reading checks every length against the file before
// tinygltf sees it, so truncation gets a precise message; writing pads JSON with spaces and
// BIN with zeros. Header-only so it needs no build entry of its own.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "core/error.h"

namespace sylva {

inline uint32_t glb_le32(const std::string& b, size_t at) {
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// Checks the container (magic, version, declared length, chunk bounds) and returns the JSON
// chunk; `length` receives the declared, verified total size. Throws InputError(path, ...),
// with "truncated" in the message when the file is shorter than its header says.
inline std::string glb_json_chunk(const std::string& path, const std::string& bytes,
                                  size_t& length) {
  if (bytes.size() < 12) throw InputError(path, "truncated: too short for a GLB header");
  if (bytes.compare(0, 4, "glTF") != 0)
    throw InputError(path, "not a binary glTF file (no 'glTF' magic at the start)");
  if (glb_le32(bytes, 4) != 2)
    throw InputError(path,
                     "unsupported GLB version " + std::to_string(glb_le32(bytes, 4)) + " (need 2)");
  length = glb_le32(bytes, 8);
  if (length > bytes.size())
    throw InputError(path, "truncated: the GLB header says " + std::to_string(length) +
                               " bytes but the file has " + std::to_string(bytes.size()));
  if (length < 20) throw InputError(path, "truncated: no JSON chunk");
  const uint64_t json_len = glb_le32(bytes, 12);
  if (glb_le32(bytes, 16) != 0x4E4F534Au) throw InputError(path, "the first GLB chunk is not JSON");
  if (20 + json_len > length) throw InputError(path, "truncated: the JSON chunk runs past the end");
  const uint64_t bin_at = 20 + json_len;
  if (bin_at < length) {
    if (bin_at + 8 > length) throw InputError(path, "truncated: incomplete BIN chunk header");
    const uint64_t bin_len = glb_le32(bytes, bin_at);
    if (bin_at + 8 + bin_len > length)
      throw InputError(path, "truncated: the BIN chunk runs past the end of the file");
  }
  return bytes.substr(20, json_len);
}

// A complete .glb from the JSON text and the BIN payload (omitted when empty).
inline std::string glb_assemble(const std::string& json, const std::string& bin) {
  std::string out(12, '\0');
  auto chunk = [&out](const std::string& data, uint32_t type, char pad) {
    const uint32_t len = uint32_t((data.size() + 3) / 4 * 4);
    out.append(reinterpret_cast<const char*>(&len), 4);
    out.append(reinterpret_cast<const char*>(&type), 4);
    out += data;
    out.append(len - data.size(), pad);
  };
  chunk(json, 0x4E4F534Au, ' ');
  if (!bin.empty()) chunk(bin, 0x004E4942u, '\0');
  const uint32_t header[3] = {0x46546C67u, 2u, uint32_t(out.size())};  // "glTF", version
  std::memcpy(out.data(), header, 12);
  return out;
}

}  // namespace sylva
