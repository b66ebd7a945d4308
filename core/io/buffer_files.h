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

namespace sylva {

struct BufferFiles {
  std::string format = "tiff";      // tiff | exr
  std::string compression = "zip";  // exr: none | zip | piz
};

// InputError naming the option and the allowed values.
void check_buffer_files(const BufferFiles& files);

// Rendered buffers (as core/gl/gbuffer.h types them), in kAllTargets order.
using BufferImages = std::vector<std::pair<Target, cv::Mat>>;

// Writes the buffers into `dir` (which exists), each file atomically: color.png, albedo.png,
// <name>.tiff and <name>.preview.png, or buffers.exr; then camera.json.
void write_buffer_files(const std::filesystem::path& dir, const BufferImages& buffers,
                        const Camera& camera, const BufferFiles& files);

}  // namespace sylva
