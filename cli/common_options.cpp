#include "cli/common_options.h"

#include <cstdio>

namespace sylva::cli {

void add_scene_options(CLI::App& cmd, SceneOptions& o) {
  cmd.add_option("scene", o.path,
                 "Scene file: .glb, .gltf (tinygltf), .obj (v, vt, vn, f), .ply (ASCII and "
                 "binary), .off (ASCII) or .stl (ASCII and binary)")
      ->required()
      ->group(kSceneGroup);
  cmd.add_option("--foliage", o.foliage,
                 "Which triangles are leaves: auto (material or mesh names containing "
                 "leaf/leaves/foliage/needle, else alpha-MASK materials), none, all, or a "
                 "case-insensitive glob on material/mesh names")
      ->capture_default_str()
      ->group(kSceneGroup);
  cmd.add_option("--clusters", o.clusters,
                 "Wanted leaf clusters: k of k-means on leaf centroids, or, for a model with a "
                 "hierarchy, the count the division diameter is chosen to come closest to; 0 = "
                 "auto, about sqrt(leaves / 2) capped at 64; [0, 4096]")
      ->capture_default_str()
      ->group(kSceneGroup);
  cmd.add_option("--seed", o.seed, "Seed for every random choice (k-means, ...)")
      ->capture_default_str()
      ->group(kSceneGroup);
}

Scene load_scene_for_cli(const SceneOptions& o, bool print_warnings) {
  Scene scene = load_clustered_scene(o);
  if (print_warnings)
    for (const std::string& w : scene.report.warning_lines())
      std::fprintf(stderr, "sylva: warning: %s: %s\n", o.path.c_str(), w.c_str());
  return scene;
}

void add_view_options(CLI::App& cmd, ViewOptions& o) {
  auto add = [&](const std::string& name, auto& value, const std::string& help) {
    cmd.add_option(name, value, help)->capture_default_str()->group(kViewGroup);
  };
  add("--size", o.size, "Image size in pixels, WxH or N, each in [1, 16384]");
  add("--azimuth", o.orbit.azimuth_deg,
      "Camera azimuth in degrees, counter-clockwise about +Y seen from above; 0 puts the camera "
      "on the +Z side looking toward -Z");
  add("--elevation", o.orbit.elevation_deg,
      "Camera elevation in degrees (raises it toward +Y), [-89, 89]");
  add("--distance", o.orbit.distance,
      "Camera distance from the bounds centre in scene units, >= 0; 0 fits the scene's bounding "
      "sphere (centred on the bounds, through the farthest vertex) in view, so the framing does "
      "not change as the camera turns");
  add("--fov", o.orbit.fov_deg, "Vertical field of view in degrees, [1, 150]");
  cmd.add_flag("--ortho", o.orbit.ortho, "Orthographic projection")->group(kViewGroup);
  add("--ssaa", o.ssaa,
      "Supersampling factor per axis, [1, 4] (colour, normal, depth, position and ka averaged; "
      "ids nearest)");
  add("--background", o.background, "white, black, transparent or #RRGGBB");
  add("--ambient", o.ambient,
      "Ambient light intensity, multiplied by the ambient coefficient "
      "ka, [0, 1]");
  cmd.add_flag("--ground", o.ground,
               "Add a ground plane at the scene's lowest point, centred under the plant: a disc "
               "30 framing radii in radius (its edge near the horizon), double-sided (role "
               "ground), ignored by the framing; with ao.model=hegeman-* it receives the crown's "
               "occlusion and hides part of the sky of the wood above it")
      ->group(kViewGroup);
  add("--ground-color", o.ground_color, "Colour of the --ground plane, #RRGGBB (sRGB)");
  add("--lod", o.lod,
      "Levels of detail for a scene of many plants: on draws each instance with a simplified "
      "mesh when it covers few pixels; off draws every one whole");
  add("--camera", o.camera,
      "A camera of the file by name or index (sylva info lists them): its place, field of view "
      "or orthographic extent and clipping planes, the image's aspect; --azimuth, --elevation, "
      "--distance, --fov and --ortho then do not apply");
  cmd.add_option("--light", o.lights,
                 "A light, repeatable up to 8, replacing the default three-light set-up (key, "
                 "fill and rim, fixed to the camera): dir|point:X,Y,Z[:INTENSITY[:camera|scene]] "
                 "- the direction toward a directional light or a point light's position, in "
                 "view space (camera, the default) or world space (scene); intensity in [0, 10], "
                 "default 1")
      ->group(kViewGroup);
  cmd.add_option("--gl", o.gl,
                 "The OpenGL backend: auto (EGL, else OSMesa), egl (a GPU's EGL device if there is "
                 "one, else Mesa's surfaceless llvmpipe), egl:N (EGL device N, from 0; sylva info "
                 "--gl lists them), osmesa (llvmpipe through OSMesa). Default: $SYLVA_GL, else "
                 "auto")
      ->group(kGlGroup);
  cmd.add_flag("--verbose", o.verbose,
               "Print the GL backend, renderer and device the command renders with on stderr")
      ->group(kGlGroup);
}

}  // namespace sylva::cli
