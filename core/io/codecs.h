// Image and video codecs outside PNG. OpenCV's imgcodecs and videoio live in the sylva_codecs
// plugin (core/io/codecs_api.h says why), dlopen()ed on the first call that needs them; PNG
// stays in process through libpng (core/io/codecs_png.h).
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <string>

#include "core/io/codecs_api.h"
#include "core/io/decode_report.h"

namespace sylva {

// The plugin's entry points, loaded once (thread-safe). The plugin is looked for at
// $SYLVA_CODECS, next to the executable (dirname of /proc/self/exe), where an install puts it
// relative to the executable (../lib/x86_64-linux-gnu/sylva/), then, for programs in the build
// tree, where this build put it. Throws std::runtime_error naming every path tried and dlerror()
// when none loads.
const CodecsApi& codecs();

// The file codecs() loaded the plugin from; throws as codecs() does.
const std::string& codecs_path();

// cv::imdecode(bytes, cv::IMREAD_UNCHANGED): PNG by libpng and JPEG by libjpeg in process (their
// messages go to `report`, never to stderr); TIFF, BMP, WebP, PNM, OpenEXR and Radiance HDR,
// known by their first bytes, by the plugin. An empty Mat when the data cannot be decoded or is
// none of those (OpenCV would also try GDCM, whose trace prints lines of its own); may throw
// cv::Exception as imdecode does, and std::runtime_error when the plugin does not load.
cv::Mat decode_image(const unsigned char* bytes, size_t size, DecodeReport* report = nullptr);

// PNG or JPEG only, in process, as glTF 2.0 allows for textures: an empty Mat for any other
// data. Never loads the plugin. `max_pixels` as decode_png and decode_jpeg take it.
cv::Mat decode_png_or_jpeg(const unsigned char* bytes, size_t size, DecodeReport* report,
                           unsigned long long max_pixels = 1ull << 30);

}  // namespace sylva
