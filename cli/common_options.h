// Options shared by the sylva subcommands: scene loading (--foliage, --clusters, --seed),
// camera and image (--size, --azimuth, --elevation, --distance, --fov, --ortho, --ssaa,
// --background, --ambient, --ground, --ground-color), the GL backend (--gl, --verbose), filling the
// library's SceneOptions and ViewOptions (styles/view.h), which parse and check them.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "styles/view.h"

namespace sylva::cli {

// The option groups several commands share (their --help headings and the README's tables,
// cli/docs.h).
inline constexpr const char* kSceneGroup = "Scene options";
inline constexpr const char* kViewGroup = "View options";
inline constexpr const char* kFoliageGroup = "Foliage illumination options";
inline constexpr const char* kStyleGroup = "Style options";
inline constexpr const char* kTurntableGroup = "Turntable options";
inline constexpr const char* kGlGroup = "GL options";

void add_scene_options(CLI::App& cmd, SceneOptions& o);
// load_clustered_scene. With `print_warnings`, the scene's warnings (one per kind) go to stderr
// as "sylva: warning: <file>: <what>" lines.
Scene load_scene_for_cli(const SceneOptions& o, bool print_warnings = true);

void add_view_options(CLI::App& cmd, ViewOptions& o);

}  // namespace sylva::cli
