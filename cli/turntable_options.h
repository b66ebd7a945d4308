// The options of `sylva turntable`, declared once: the turntable command registers and checks
// them, and `sylva farm slurm` registers the same ones and passes them on to its tasks.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "cli/common_options.h"
#include "cli/illumination_options.h"
#include "styles/frame_folder.h"
#include "styles/style.h"
#include "styles/turntable.h"

namespace sylva::cli {

struct TurntableOptions {
  SceneOptions scene;
  ViewOptions view;
  FoliageRunOptions foliage;
  std::string style = "standard";
  std::vector<std::string> sets;
  TurntablePath path;
  std::string axis = "y";
  double fps = 30;
  std::string range, report, out, keyframe_cache, frame_format = "png";
  double dpi = 0.0;
  int keyframe_every = 1;
  bool resume = false, quiet = false, keyframes_only = false;
};

// Registers every turntable option on `cmd` (the scene, view, illumination and style options,
// the path, the outputs); `-o` is required.
void add_turntable_options(CLI::App& cmd, TurntableOptions& o);

// What the checked options mean.
struct TurntableChecks {
  bool to_dir = false;                          // frames into a folder (not an MP4 or GIF)
  bool blobs = false;                           // the style paints blobs
  bool vector = false;                          // svg or pdf frames
  FrameFormat frame_format = FrameFormat::Png;  // --frame-format
  FrameRange range;
  std::unique_ptr<Style> style;
};

// Checks every option before any work (InputError naming the option), resolves the style.
TurntableChecks check_turntable_options(const CLI::App& cmd, TurntableOptions& o);

}  // namespace sylva::cli
