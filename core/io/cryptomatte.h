// Cryptomatte layers in an EXR (Psyop's Cryptomatte specification, v1.1/1.2): names are hashed
// with MurmurHash3_x86_32 (seed 0, libmurmurhash), the hash's bits become a float32 id with the
// exponent clamped to [1, 254] ("uint32_to_float32"), and each pixel stores its ids ranked by
// coverage as (id, coverage) pairs: <layer>00.R/G = rank 0, <layer>00.B/A = rank 1,
// <layer>01.R/G = rank 2, ... Coverage is the share of the pixel's SSAA samples (the box
// filter of the colour) that hit the id, so a pixel's coverages sum to its alpha; the
// background is no id (0, coverage 0). The header gets cryptomatte/<key>/name, /hash,
// /conversion and /manifest (JSON: name -> 8 hex digits of the float id's bits), with <key>
// the first 7 hex digits of the layer name's hash.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/exr_writer.h"

namespace sylva {

uint32_t murmur3_32(std::string_view data);  // seed 0
float cryptomatte_id(uint32_t hash);         // uint32_to_float32
std::string cryptomatte_hex(float id);       // "%08x" of the float's bits

struct CryptomatteLayer {
  std::string name;                // e.g. CryptoObject
  std::vector<std::string> names;  // names[k] is id k + 1 of the id samples
};

// Adds ranks / 2 RGBA float layers (<name>00, <name>01, ...) and the metadata. `samples`:
// CV_32SC1 ids, `factor` x the image's size per axis (0 = nothing; an id beyond `names` is a
// programming error). ranks: even, [2, 16]. Ids that tie on coverage rank by their float id.
void add_cryptomatte(ExrImage& exr, const CryptomatteLayer& layer, const cv::Mat& samples,
                     int factor, int ranks);

}  // namespace sylva
