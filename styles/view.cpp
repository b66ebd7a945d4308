#include "styles/view.h"

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

namespace sylva {

Scene load_clustered_scene(const SceneOptions& o) {
  LoadOptions lo;
  lo.foliage = o.foliage;
  Scene scene = load_scene(o.path, lo);
  ClusterOptions co;
  co.clusters = o.clusters;
  co.seed = o.seed;
  assign_clusters(scene, co);
  return scene;
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
glm::vec4 linear_of_hex(const std::string& s) {
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
  return linear_of_hex(s);
}

glm::vec4 parse_ground_color(const std::string& s) {
  static const std::regex re("^#([0-9a-fA-F]{6})$");
  if (!std::regex_match(s, re))
    throw InputError("--ground-color", "expected #RRGGBB, got '" + s + "'");
  return linear_of_hex(s);
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

}  // namespace sylva
