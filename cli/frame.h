// What the rendering commands (render, buffers, compare, turntable) share: the loaded and
// uploaded scene of one view (the library's Frame, styles/frame.h) and the style options (the
// files: styles/style_files.h).
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "cli/common_options.h"
#include "cli/illumination_options.h"
#include "core/cache/result_cache.h"
#include "styles/frame.h"
#include "styles/sheet.h"
#include "styles/style.h"
#include "styles/style_files.h"

namespace sylva::cli {

// Resolves the view options, loads the scene (its warnings on stderr) and makes its frame
// (make_frame) with the result cache folder `cache_dir` ("" = none).
std::unique_ptr<Frame> prepare_frame(const SceneOptions& so, ViewOptions& vo,
                                     const std::string& cache_dir = default_cache_dir());

// --style NAME|FILE.toml and --set section.key=value (repeatable).
void add_style_options(CLI::App& cmd, std::string& style, std::vector<std::string>& sets);

// The style named by --style with the --set overrides and the foliage options given
// explicitly on the command line applied (in that order).
std::unique_ptr<Style> resolve_style(const CLI::App& cmd, const std::string& name,
                                     const std::vector<std::string>& sets);

// The frame as a contact sheet's shared scene (make_sheet_scene); `run` is the preprocessing's
// cache and outputs and the seed comes from the scene options.
SheetScene sheet_scene(const Frame& frame, const FoliageRun& run, uint64_t seed);

// Vector output (.svg, .pdf): whether `path` asks for it.
bool is_vector_path(const std::string& path);

}  // namespace sylva::cli
