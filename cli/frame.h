// What the rendering commands (render, buffers, compare) share: the loaded and uploaded
// scene of one view, the style options, and turning a style's image into a file.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "cli/common_options.h"
#include "cli/illumination_options.h"
#include "core/cache/result_cache.h"
#include "core/gl/raster_pass.h"
#include "core/io/svg_writer.h"
#include "styles/sheet.h"
#include "styles/style.h"

namespace sylva::cli {

// Everything a frame needs: the loaded scene, a GL context and an uploaded rasteriser.
struct Frame {
  Scene scene;
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Rasterizer> rasterizer;
  RasterSetup setup;
};

// Resolves the view options, loads the scene and uploads it, with its plants' levels of
// detail (npr/plant_lod.h) unless --lod off, read from or stored in the result cache folder
// `cache_dir` ("" = none).
std::unique_ptr<Frame> prepare_frame(const SceneOptions& so, ViewOptions& vo,
                                     const std::string& cache_dir = default_cache_dir());
// The graph's results are plain images: drop the scene, the GL objects and the context
// before encoding files, and hand freed heap back, so peak memory is not their sum.
void release_frame(std::unique_ptr<Frame>& frame);

// --style NAME|FILE.toml and --set section.key=value (repeatable).
void add_style_options(CLI::App& cmd, std::string& style, std::vector<std::string>& sets);

// The style named by --style with the --set overrides and the foliage options given
// explicitly on the command line applied (in that order); `io` receives the resulting foliage
// settings with the run-only ones (--surface-out, cache) kept.
std::unique_ptr<Style> resolve_style(const CLI::App& cmd, const std::string& name,
                                     const std::vector<std::string>& sets, IlluminationOptions& io);

// The frame as a contact sheet's shared scene; `run` supplies the run-only foliage options
// (cache, --surface-out) and the seed comes from the scene options.
SheetScene sheet_scene(const Frame& frame, const IlluminationOptions& run, uint64_t seed);

// Writes a style's BGRA image as .png or .tiff (with alpha), .jpg (alpha dropped) or .exr
// (linear half R, G, B premultiplied, A), atomically; `dpi` > 0 goes into a PNG's pHYs, a
// TIFF's resolution or an EXR's xDensity. bit_depth 16 (PNG, TIFF) widens the 8-bit values
// (v x 257).
void write_styled_image(const std::string& path, const cv::Mat& bgra, double dpi = 0.0,
                        int bit_depth = 8);

// Vector output (.svg, .pdf): whether `path` asks for it; InputError(option, ...) naming the
// styles that can when `style` draws no strokes.
bool is_vector_path(const std::string& path);
void require_line_style(const Style& style, const std::string& option);
// The page of a style's vector drawing: its paper (ink.paper_color; none when ink.transparent
// or the view's background is "transparent") and the dpi.
VectorPage vector_page(const Style& style, const ViewOptions& view, double dpi);
// Writes a drawing as .svg or .pdf (by the extension), atomically.
void write_vector_drawing(const std::string& path, const StrokeDrawing& d, const VectorPage& page);

}  // namespace sylva::cli
