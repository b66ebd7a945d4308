#include "npr/ao_pass.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "core/scene/instances.h"
#include "core/scene/texture_alpha.h"
#include "npr/ao_plants.h"
#include "npr/ao_reference.h"
#include "npr/ao_uniforms.h"

namespace sylva {

namespace {

constexpr int kFitRays = 64;

bool parse_number(const std::string& text, double& v) {
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, v);
  return !text.empty() && ec == std::errc() && p == end && std::isfinite(v);
}

}  // namespace

const std::vector<std::pair<std::string, AoModel>>& ao_model_choices() {
  static const std::vector<std::pair<std::string, AoModel>> c = {
      {"none", AoModel::None},
      {"constant", AoModel::Constant},
      {"luft-density", AoModel::LuftDensity},
      {"hegeman-sphere", AoModel::HegemanSphere},
      {"hegeman-ellipsoid", AoModel::HegemanEllipsoid},
      {"hegeman-shells", AoModel::HegemanShells},
      {"raytraced", AoModel::Raytraced}};
  return c;
}

AoModel parse_ao_model(const std::string& name, const std::string& where) {
  std::string allowed;
  for (const auto& [n, model] : ao_model_choices()) {
    if (n == name) return model;
    allowed += (allowed.empty() ? "" : ", ") + n;
  }
  throw InputError(where, "unknown model '" + name + "' (allowed: " + allowed + ")");
}

const std::string& ao_model_name(AoModel model) {
  for (const auto& [n, m] : ao_model_choices())
    if (m == model) return n;
  throw InputError("ao.model", "holds none of the models");
}

void bind_ao_params(ParamSet& set, AoSettings& s) {
  set.add_choice("ao.model", s.model, ao_model_choices(),
                 "ambient occlusion multiplying the ambient term and written to the ao buffer");
  set.add_float("ao.constant", s.constant, 0, 1, "", "visibility of ao.model = constant");
  set.add_text(
      "ao.alpha_rho", s.alpha_rho,
      [](const std::string& text, const std::string& where) {
        double v = 0;
        if (text == "auto") return;
        if (!parse_number(text, v) || v < 0.0 || v > 3.4e38)
          throw InputError(where, "must be 'auto' or a number >= 0, got '" + text + "'");
      },
      "auto or a number >= 0 (per scene unit cubed)",
      "Hegeman Eq. 6 occluder density x size; auto = fitted to ray-traced AO");
  set.add_int("ao.shells", s.shells, 1, kMaxAoShells, "shells",
              "k of ao.model = hegeman-shells (k-means clusters of the foliage)");
  set.add_choice("ao.solid_angle", s.solid_angle,
                 {{"exact", SolidAngleModel::Exact}, {"paper", SolidAngleModel::Paper}},
                 "hegeman-*: the crown's solid angle darkening wood, ground and grass "
                 "(Hegeman Eq. 7-8): exact or the paper's pi (r/d)^2");
  set.add_int("ao.rays", s.rays, 1, 4096, "rays per pixel", "rays of ao.model = raytraced");
}

AoShading::Model ao_model_of(AoModel model) {
  switch (model) {
    case AoModel::None:
    case AoModel::Raytraced:
      return AoShading::Model::None;
    case AoModel::Constant:
      return AoShading::Model::Constant;
    case AoModel::LuftDensity:
      return AoShading::Model::Ka;
    case AoModel::HegemanSphere:
    case AoModel::HegemanEllipsoid:
    case AoModel::HegemanShells:
      return AoShading::Model::Shells;
  }
  throw InputError("ao.model", "holds none of the models");
}

AoReferenceScene make_scene_tracer(const Scene& input) {
  // Embree traces world-space triangles: an instanced scene is flattened.
  const Scene flat = input.instanced() ? flatten(input) : Scene{};
  const Scene& scene = input.instanced() ? flat : input;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  std::vector<uint32_t> indices;
  std::vector<int> triangle_material;
  bool any_cutout = false;
  for (const Mesh& m : scene.meshes) {
    const auto base = static_cast<uint32_t>(positions.size());
    positions.insert(positions.end(), m.positions.begin(), m.positions.end());
    if (m.uvs.size() == m.positions.size()) {
      uvs.insert(uvs.end(), m.uvs.begin(), m.uvs.end());
    } else {
      uvs.resize(positions.size(), glm::vec2(0.0f));
    }
    for (uint32_t i : m.indices)
      indices.push_back(base + i);
    int cutout = -1;
    if (m.material >= 0 && size_t(m.material) < scene.materials.size() &&
        is_cutout(scene, scene.materials[size_t(m.material)]))
      cutout = m.material;
    any_cutout = any_cutout || cutout >= 0;
    triangle_material.insert(triangle_material.end(), m.triangle_count(), cutout);
  }
  if (!any_cutout) return AoReferenceScene(positions, indices);
  const Scene* s = &input;  // materials and textures: the same in the flattened scene
  auto materials = std::make_shared<const std::vector<int>>(std::move(triangle_material));
  auto alpha = [s, materials](uint32_t triangle, glm::vec2 uv) -> float {
    return drawn_at(*s, s->materials[size_t((*materials)[triangle])], uv) ? 1.0f : 0.0f;
  };
  auto cutout_triangle = [materials](uint32_t triangle) { return (*materials)[triangle] >= 0; };
  AoHitFilter filter = make_alpha_cutout_filter(uvs, indices, alpha, 0.5f, cutout_triangle);
  return AoReferenceScene(positions, indices, std::move(filter));
}

std::vector<glm::vec3> foliage_vertices(const Scene& scene) {
  std::vector<glm::vec3> out;
  for (const Mesh& m : scene.meshes) {
    std::vector<char> used(m.positions.size(), 0);
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      if (t < m.roles.size() && m.roles[t] != Role::Foliage) continue;
      if (m.roles.empty()) continue;
      for (int k = 0; k < 3; ++k)
        used[m.indices[3 * t + k]] = 1;
    }
    for (size_t v = 0; v < used.size(); ++v)
      if (used[v]) out.push_back(m.positions[v]);
  }
  return out;
}

AoShading scene_ao_shading(const Scene& scene, const AoSettings& s, uint64_t seed) {
  if (scene.instanced()) return plants_ao_shading(scene, s, seed);
  AoShading ao;
  ao.model = ao_model_of(s.model);
  ao.constant = s.constant;
  if (ao.model != AoShading::Model::Shells) return ao;
  if (s.solid_angle != SolidAngleModel::Exact && s.solid_angle != SolidAngleModel::Paper)
    throw InputError("ao.solid_angle", "must be exact or paper");
  const std::vector<glm::vec3> points = foliage_vertices(scene);
  Bounds grass, ground;  // of the Role::Grass and Role::Ground triangles (none without roles)
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count() && t < m.roles.size(); ++t) {
      if (m.roles[t] != Role::Grass && m.roles[t] != Role::Ground) continue;
      for (int k = 0; k < 3; ++k)
        (m.roles[t] == Role::Grass ? grass : ground)
            .extend(m.positions[m.indices[3 * t + size_t(k)]]);
    }
  // A flat ground (all its vertices at one height, as `--ground` makes) is taken as an
  // infinite plane that also hides part of the sky of wood and other geometry above it.
  const bool flat_ground =
      !ground.empty() && ground.max.y - ground.min.y <= 1e-6f * std::max(1.0f, ground.diagonal());
  auto finish = [&](AoShading out) {
    out.exact_solid_angle = s.solid_angle == SolidAngleModel::Exact;
    out.ground_plane = flat_ground;
    out.ground_y = flat_ground ? ground.min.y : 0.0f;
    if (!grass.empty()) {
      out.grass_ground = grass.min.y;  // Hegeman et al. Eq. 9: P_z from the roots, h the field
      out.grass_height = grass.max.y - grass.min.y;
    }
    return out;
  };
  if (points.empty() && !grass.empty()) return finish(ao);
  if (points.empty())
    throw InputError("ao.model", "'" + ao_model_name(s.model) + "' needs foliage");
  AoShellFit fit;
  fit.ellipsoid = s.model != AoModel::HegemanSphere;
  fit.shells = s.model == AoModel::HegemanShells ? s.shells : 1;
  fit.seed = seed;
  if (s.alpha_rho == "auto") {
    for (const Mesh& m : scene.meshes)
      for (size_t t = 0; t < m.triangle_count() && t < m.roles.size(); ++t) {
        if (m.roles[t] != Role::Foliage) continue;
        const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                        c = m.positions[m.indices[3 * t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        if (!(glm::dot(n, n) > 0.0f)) continue;
        fit.sample_points.push_back((a + b + c) / 3.0f);
        fit.sample_normals.push_back(glm::normalize(n));
      }
    const Scene* sc = &scene;
    fit.trace = [sc, seed](const std::vector<glm::vec3>& p, const std::vector<glm::vec3>& n) {
      AoReferenceOptions options;
      options.rays = kFitRays;
      options.seed = seed;
      return make_scene_tracer(*sc).visibility(p, n, options);
    };
  } else {
    double v = 0.0;
    if (!parse_number(s.alpha_rho, v) || v < 0.0)
      throw InputError("ao.alpha_rho", "must be 'auto' or a number >= 0");
    fit.alpha_rho = float(v);
  }
  return finish(fit_ao_shading(points, fit));
}

std::string ao_memo_key(const AoSettings& s, uint64_t seed) {
  return ao_model_name(s.model) + ";" + std::to_string(s.constant) + ";" + s.alpha_rho + ";" +
         std::to_string(s.shells) + ";" +
         (s.solid_angle == SolidAngleModel::Exact ? "exact" : "paper") + ";" + std::to_string(seed);
}

Handle<std::shared_ptr<const AoShading>> add_ao_shading_pass(RenderGraph& graph, AoSetup setup) {
  SYLVA_CHECK(setup.scene != nullptr, "AO shading needs a scene");
  const auto out = graph.resource<std::shared_ptr<const AoShading>>("ao-shading");
  graph.add_pass("ao-shells", {}, {out}, [out, setup](PassContext& ctx) {
    std::shared_ptr<const AoShading> ao;
    const std::string key = setup.memo ? ao_memo_key(setup.settings, setup.seed) : "";
    if (setup.memo) {
      const std::lock_guard<std::mutex> lock(setup.memo->mutex);
      auto it = setup.memo->shading.find(key);
      if (it != setup.memo->shading.end()) ao = it->second;
    }
    if (!ao) {
      ao = std::make_shared<const AoShading>(
          scene_ao_shading(*setup.scene, setup.settings, setup.seed));
      if (setup.memo) {
        const std::lock_guard<std::mutex> lock(setup.memo->mutex);
        setup.memo->shading.emplace(key, ao);
      }
    }
    ctx.write(out, ao);
  });
  return out;
}

}  // namespace sylva

namespace sylva {

Handle<cv::Mat> add_raytraced_ao_pass(RenderGraph& graph, const Scene* scene,
                                      Handle<cv::Mat> position, Handle<cv::Mat> normal,
                                      const glm::mat4& view, int rays, uint64_t seed,
                                      std::shared_ptr<AoMemo> memo) {
  SYLVA_CHECK(scene != nullptr, "ray-traced AO needs a scene");
  const auto out = graph.resource<cv::Mat>("ao-raytraced");
  const glm::mat4 to_world = glm::inverse(view);
  graph.add_pass("ao-raytraced", {position, normal}, {out}, [=](PassContext& ctx) {
    const cv::Mat& pos = ctx.read(position);
    const cv::Mat& nor = ctx.read(normal);
    SYLVA_CHECK(pos.type() == CV_32FC3 && nor.type() == CV_32FC3 && pos.size() == nor.size(),
                "ray-traced AO reads view-space position and normal targets");
    std::vector<glm::vec3> points, normals;
    std::vector<int> pixels;
    for (int y = 0; y < pos.rows; ++y)
      for (int x = 0; x < pos.cols; ++x) {
        const cv::Vec3f n = nor.at<cv::Vec3f>(y, x);
        if (n == cv::Vec3f(0, 0, 0)) continue;  // background
        const cv::Vec3f p = pos.at<cv::Vec3f>(y, x);
        points.push_back(glm::vec3(to_world * glm::vec4(p[0], p[1], p[2], 1.0f)));
        normals.push_back(glm::mat3(to_world) * glm::vec3(n[0], n[1], n[2]));
        pixels.push_back(y * pos.cols + x);
      }
    cv::Mat ao = cv::Mat::zeros(pos.size(), CV_32FC1);
    if (!points.empty()) {
      std::shared_ptr<const AoReferenceScene> tracer;
      if (memo) {
        const std::lock_guard<std::mutex> lock(memo->mutex);
        if (!memo->tracer)
          memo->tracer = std::make_shared<const AoReferenceScene>(make_scene_tracer(*scene));
        tracer = memo->tracer;
      } else {
        tracer = std::make_shared<const AoReferenceScene>(make_scene_tracer(*scene));
      }
      AoReferenceOptions options;
      options.rays = rays;
      options.seed = seed;
      const std::vector<float> v = tracer->visibility(points, normals, options);
      for (size_t i = 0; i < pixels.size(); ++i)
        ao.at<float>(pixels[i] / pos.cols, pixels[i] % pos.cols) = v[i];
    }
    ctx.write(out, ao);
  });
  return out;
}

}  // namespace sylva
