// A view of a scene as a program asks for it: the options that load a scene (SceneOptions:
// the foliage rule, clusters, seed) and those that frame and light it (ViewOptions: size,
// camera, supersampling, background, ambient, lights, ground), parsed and range-checked. The
// CLI fills them from its options (cli/common_options.h) and the Python module from keyword
// arguments, so both load and frame a scene the same way. Errors are InputError naming the
// CLI option ("--size").
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/gl/camera.h"
#include "core/gl/gl_context.h"
#include "core/gl/lights.h"
#include "core/gl/rasterizer.h"
#include "core/scene/scene.h"

namespace sylva {

struct SceneOptions {
  std::string path;
  std::string foliage = "auto";  // LoadOptions::foliage
  int clusters = 0;              // ClusterOptions::clusters; [0, 4096], 0 = auto
  uint64_t seed = 1;             // every random choice (k-means, ...)
};
// Loads, classifies and clusters. Throws InputError on bad input; the scene's warnings are in
// scene.report.
Scene load_clustered_scene(const SceneOptions& o);

struct ViewOptions {
  std::string size = "1024x1024";
  OrbitParams orbit;
  int ssaa = 1;
  std::string background = "white";
  float ambient = 0.35f;
  std::string id_kind = "primitive";
  std::vector<std::string> lights;  // --light specs; empty = the three-light default
  // --ground: a ground plane under the scene (core/scene/ground_plane.h); off by default.
  bool ground = false;
  // --ground-color: "#RRGGBB" (sRGB, as --background) of the ground plane; a neutral light
  // grey by default.
  std::string ground_color = "#b4b4ac";
  // --lod on|off: levels of detail for the instances of a scene of many plants.
  std::string lod = "on";
  // --camera NAME|INDEX: a camera of the file (Scene::cameras, `sylva info` lists them) in
  // place of the orbit camera; empty = the orbit camera.
  std::string camera;
  // --gl auto|egl|egl:N|osmesa: the GL backend (core/gl/gl_context.h); "" = $SYLVA_GL, else
  // auto. Every command with the view options renders, so it carries the GL options too.
  std::string gl;
  // --verbose: the backend, renderer and device taken, on stderr.
  bool verbose = false;
  int width = 0, height = 0;  // parsed from size
  GlChoice gl_choice;         // parsed from gl and the environment
};
// Parses and range-checks the view options (size, ssaa, background, ambient, id kind,
// ground colour, GL backend).
void resolve_view_options(ViewOptions& o);
// A context of the backend the options choose (create_gl_context); with --verbose, says on
// stderr which backend, renderer and device it is ("sylva: GL: ...").
std::unique_ptr<GlContext> start_gl(const ViewOptions& o);
// The lines `sylva info --gl` and --verbose print about `context`: "backend  EGL (surfaceless)".
std::vector<std::pair<std::string, std::string>> gl_facts(const GlContext& context);
// The view's camera: the file's camera named by --camera (make_file_camera), else the orbit
// camera framing the scene with its depth range fitted to the whole scene. Throws
// InputError("--camera", ...) naming the file's cameras when none matches.
Camera view_camera(const Scene& scene, const ViewOptions& o);
// The file camera `name_or_index` names: an index in [0, cameras) or a name (exact).
const SceneCamera& find_file_camera(const Scene& scene, const std::string& name_or_index);

// Adds the ground plane to the loaded scene when --ground is given.
void apply_ground_option(Scene& scene, const ViewOptions& o);
RasterRequest raster_request(const ViewOptions& o);
Lighting lighting_for(const ViewOptions& o);

// "WxH" or "N" (square); each in [1, 16384]. Throws InputError("--size", ...).
void parse_size(const std::string& s, int& width, int& height);
// "dir|point:X,Y,Z[:INTENSITY[:camera|scene]]"; intensity in [0, 10], default 1; camera-fixed
// by default. Throws InputError("--light", ...).
Light parse_light(const std::string& spec);
// "white", "black", "transparent" or "#RRGGBB"; returns linear RGBA.
glm::vec4 parse_background(const std::string& s);
// "#RRGGBB" (sRGB); returns linear RGBA, alpha 1. Throws InputError("--ground-color", ...).
glm::vec4 parse_ground_color(const std::string& s);

}  // namespace sylva
