#include "cli/common_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>

#include "core/color.h"
#include "core/error.h"
#include "core/gl/depth_range.h"
#include "core/scene/ground_plane.h"
#include "core/scene/load.h"
#include "npr/leaf_clusters.h"

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
  LoadOptions lo;
  lo.foliage = o.foliage;
  Scene scene = load_scene(o.path, lo);
  ClusterOptions co;
  co.clusters = o.clusters;
  co.seed = o.seed;
  assign_clusters(scene, co);
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

void parse_size(const std::string& s, int& width, int& height) {
  static const std::regex re(R"(^\s*(\d{1,6})\s*(?:[xX]\s*(\d{1,6}))?\s*$)");
  std::smatch m;
  if (!std::regex_match(s, m, re))
    throw InputError("--size", "expected WxH or N in pixels, got '" + s + "'");
  width = std::stoi(m[1]);
  height = m[2].matched ? std::stoi(m[2]) : width;
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError("--size", "each side must be in [1, 16384] pixels, got '" + s + "'");
}

namespace {

// "#RRGGBB", already checked: linear RGBA with alpha 1.
glm::vec4 hex_color(const std::string& s) {
  unsigned v = std::stoul(s.substr(1), nullptr, 16);
  auto lin = [](unsigned c) {  // sRGB to linear, so '#808080' means the grey the user sees
    return srgb_to_linear(c / 255.0f);
  };
  return {lin((v >> 16) & 255), lin((v >> 8) & 255), lin(v & 255), 1.0f};
}

}  // namespace

glm::vec4 parse_background(const std::string& s) {
  if (s == "white") return {1, 1, 1, 1};
  if (s == "black") return {0, 0, 0, 1};
  if (s == "transparent") return {1, 1, 1, 0};
  static const std::regex re("^#([0-9a-fA-F]{6})$");
  if (!std::regex_match(s, re))
    throw InputError("--background",
                     "expected white, black, transparent or #RRGGBB, got '" + s + "'");
  return hex_color(s);
}

glm::vec4 parse_ground_color(const std::string& s) {
  static const std::regex re("^#([0-9a-fA-F]{6})$");
  if (!std::regex_match(s, re))
    throw InputError("--ground-color", "expected #RRGGBB, got '" + s + "'");
  return hex_color(s);
}

Light parse_light(const std::string& spec) {
  static const std::regex re(
      R"(^(dir|point):([-+0-9.eE]+),([-+0-9.eE]+),([-+0-9.eE]+)(?::([-+0-9.eE]+))?(?::(camera|scene))?$)");
  std::smatch m;
  if (!std::regex_match(spec, m, re))
    throw InputError("--light",
                     "expected dir|point:X,Y,Z[:INTENSITY[:camera|scene]], got '" + spec + "'");
  Light l;
  l.type = m[1] == "dir" ? Light::Type::Directional : Light::Type::Point;
  try {
    l.vector = {std::stof(m[2]), std::stof(m[3]), std::stof(m[4])};
    float intensity = m[5].matched ? std::stof(m[5]) : 1.0f;
    if (!(intensity >= 0.0f && intensity <= 10.0f))
      throw InputError("--light", "intensity must be in [0, 10] in '" + spec + "'");
    l.color = glm::vec3(intensity);
  } catch (const std::logic_error&) {
    throw InputError("--light", "not a number in '" + spec + "'");
  }
  if (!std::isfinite(l.vector.x) || !std::isfinite(l.vector.y) || !std::isfinite(l.vector.z))
    throw InputError("--light", "not a finite vector in '" + spec + "'");
  if (l.type == Light::Type::Directional && glm::length(l.vector) < 1e-6f)
    throw InputError("--light", "direction must not be zero in '" + spec + "'");
  l.camera_fixed = !(m[6].matched && m[6] == "scene");
  l.specular = 0.2f;
  return l;
}

void resolve_view_options(ViewOptions& o) {
  parse_size(o.size, o.width, o.height);
  if (o.ssaa < 1 || o.ssaa > 4)
    throw InputError("--ssaa", "must be in [1, 4], got " + std::to_string(o.ssaa));
  if (static_cast<long long>(o.width) * o.ssaa > 16384 ||
      static_cast<long long>(o.height) * o.ssaa > 16384)
    throw InputError("--ssaa", "size x ssaa must stay within 16384 pixels per side");
  if (!(o.ambient >= 0.0f && o.ambient <= 1.0f)) throw InputError("--ambient", "must be in [0, 1]");
  parse_background(o.background);
  parse_ground_color(o.ground_color);
  if (o.lights.size() > 8) throw InputError("--light", "at most 8 lights");
  for (const std::string& l : o.lights)
    parse_light(l);
  if (o.lod != "on" && o.lod != "off")
    throw InputError("--lod", "expected on or off, got '" + o.lod + "'");
  if (o.id_kind != "primitive" && o.id_kind != "cluster" && o.id_kind != "object" &&
      o.id_kind != "material")
    throw InputError("--id",
                     "expected primitive, cluster, object or material, got '" + o.id_kind + "'");
  o.gl_choice = gl_choice_from_option(o.gl);
}

std::vector<std::pair<std::string, std::string>> gl_facts(const GlContext& context) {
  const GlInfo& i = context.info();
  std::string backend = i.backend == GlBackend::Egl ? "EGL (" + i.platform + ")" : "OSMesa";
  std::vector<std::pair<std::string, std::string>> facts = {
      {"backend", backend},   {"device", i.device.empty() ? "-" : i.device},
      {"vendor", i.vendor},   {"renderer", i.renderer + (i.software ? " (CPU)" : "")},
      {"version", i.version}, {"platform", i.window_system}};
  if (!i.fallback.empty()) facts.push_back({"fallback", i.fallback});
  return facts;
}

std::unique_ptr<GlContext> start_gl(const ViewOptions& o) {
  std::unique_ptr<GlContext> context = create_gl_context(o.gl_choice);
  if (o.verbose)
    for (const auto& [key, value] : gl_facts(*context))
      std::fprintf(stderr, "sylva: GL %s: %s\n", key.c_str(), value.c_str());
  return context;
}

const SceneCamera& find_file_camera(const Scene& scene, const std::string& text) {
  std::string names;
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    names += (i ? ", " : "") + std::to_string(i) + " '" + scene.cameras[i].name + "' (" +
             (scene.cameras[i].orthographic ? "orthographic" : "perspective") + ")";
  const std::string listing =
      scene.cameras.empty() ? "the file has no cameras" : "the file's cameras: " + names;
  const bool digits =
      !text.empty() && text.size() < 10 &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits) {
    const size_t i = std::stoul(text);
    if (i < scene.cameras.size()) return scene.cameras[i];
    throw InputError("--camera", "index " + text + " is out of range; " + listing);
  }
  for (const SceneCamera& c : scene.cameras)
    if (c.name == text) return c;
  throw InputError("--camera", "no camera named '" + text + "'; " + listing);
}

Camera view_camera(const Scene& scene, const ViewOptions& o) {
  if (!o.camera.empty())
    return make_file_camera(find_file_camera(scene, o.camera), scene.framing_sphere(), o.width,
                            o.height);
  Camera camera = make_orbit_camera(scene.framing_sphere(), o.orbit, o.width, o.height);
  fit_camera_depth(camera, scene);
  return camera;
}

void apply_ground_option(Scene& scene, const ViewOptions& o) {
  if (o.ground) add_ground_plane(scene, parse_ground_color(o.ground_color));
}

RasterRequest raster_request(const ViewOptions& o) {
  RasterRequest r;
  r.ssaa = o.ssaa;
  r.background = parse_background(o.background);
  r.id_kind = o.id_kind == "cluster"    ? IdKind::Cluster
              : o.id_kind == "object"   ? IdKind::Object
              : o.id_kind == "material" ? IdKind::Material
                                        : IdKind::Primitive;
  return r;
}

Lighting lighting_for(const ViewOptions& o) {
  Lighting l = Lighting::three_point();
  if (!o.lights.empty()) {
    l.lights.clear();
    for (const std::string& spec : o.lights)
      l.lights.push_back(parse_light(spec));
  }
  l.ambient = o.ambient;
  return l;
}

}  // namespace sylva::cli
