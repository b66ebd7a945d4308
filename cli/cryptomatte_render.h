// The Cryptomatte layers of `sylva buffers --format exr`: the id target rendered once per kind
// (objects = the scene's meshes, materials, assets = leaf clusters) with its SSAA samples kept,
// and the names the ids stand for.
#pragma once

#include <string>
#include <vector>

#include "cli/frame.h"
#include "core/io/buffer_files.h"

namespace sylva::cli {

// `list`: comma-separated object, material, asset; or none. InputError("--cryptomatte", ...)
// for anything else.
std::vector<std::string> parse_cryptomatte_list(const std::string& list);

// One CryptoObject / CryptoMaterial / CryptoAsset layer per kind, in the list's order.
std::vector<CryptomatteImage> render_cryptomattes(Frame& frame,
                                                  const std::vector<std::string>& kinds);

}  // namespace sylva::cli
