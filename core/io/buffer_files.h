// The files `sylva buffers` writes: one lossless file per buffer (TIFF, PNG for the colours) or
// one multi-channel OpenEXR (`--format exr`), with camera.json beside either.
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "core/gl/camera.h"
#include "core/gl/gbuffer.h"
#include "core/io/cryptomatte.h"

namespace sylva {

struct BufferFiles {
  std::string format = "tiff";                        // tiff | exr
  std::string compression = "zip";                    // exr: none | zip | piz
  std::string cryptomatte = "object,material,asset";  // exr: the layers, or none
};

// One Cryptomatte layer's names and id samples (core/io/cryptomatte.h).
struct CryptomatteImage {
  CryptomatteLayer layer;
  cv::Mat samples;  // CV_32SC1, factor x the image size
  int factor = 1;
};

// Ranks (id, coverage pairs) per Cryptomatte layer: 2 (one RGBA layer, 00) when each pixel is
// one sample; with SSAA the specification's suggested 6 (00, 01, 02).
inline int cryptomatte_ranks(int factor) {
  return factor > 1 ? 6 : 2;
}

// InputError naming the option and the allowed values.
void check_buffer_files(const BufferFiles& files);

// Rendered buffers (as core/gl/gbuffer.h types them), in kAllTargets order.
using BufferImages = std::vector<std::pair<Target, cv::Mat>>;

// camera.json: the image size, near and far planes, eye, and the view and projection matrices
// (row-major rows, column vectors: p_view = view * p_world).
std::string camera_json(const Camera& camera);

// Writes the buffers into `dir` (which exists), each file atomically: color.png, albedo.png,
// <name>.tiff and <name>.preview.png, or buffers.exr (with the Cryptomatte layers); then
// camera.json.
void write_buffer_files(const std::filesystem::path& dir, const BufferImages& buffers,
                        const Camera& camera, const BufferFiles& files,
                        const std::vector<CryptomatteImage>& mattes = {});

}  // namespace sylva
