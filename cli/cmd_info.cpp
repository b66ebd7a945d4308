// sylva info SCENE [--json]: what the scene holds (triangles drawn and distinct, instances,
// plants, cameras, ...) and what the loader decided. sylva info --gl [BACKEND]: the GL backend
// a rendering command would take (backend, device, vendor, renderer, version), the backends
// built and the EGL devices; the scene is then optional.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/gl/gl_context.h"
#include "core/scene/instances.h"

namespace sylva::cli {

namespace {

// Per plant: name, meshes, stored triangles and instances (a flat scene: one, "scene").
nlohmann::json describe_plants(const Scene& scene) {
  nlohmann::json out = nlohmann::json::array();
  for (size_t p = 0; p < scene.plant_count(); ++p) {
    size_t triangles = 0;
    const std::vector<uint32_t> meshes = plant_meshes(scene, p);
    for (uint32_t m : meshes)
      triangles += scene.meshes[m].triangle_count();
    out.push_back({{"name", scene.instanced() ? scene.plants[p].name : "scene"},
                   {"meshes", meshes.size()},
                   {"triangles", triangles},
                   {"instances", plant_instances(scene, p).size()}});
  }
  return out;
}

nlohmann::json describe_cameras(const Scene& scene) {
  nlohmann::json out = nlohmann::json::array();
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const SceneCamera& c = scene.cameras[i];
    const glm::vec3 eye(c.to_world[3]);
    nlohmann::json j = {{"index", i},
                        {"name", c.name},
                        {"type", c.orthographic ? "orthographic" : "perspective"},
                        {"eye", {eye.x, eye.y, eye.z}},
                        {"znear", c.znear},
                        {"zfar", c.zfar}};
    if (c.orthographic) {
      j["xmag"] = c.xmag;
      j["ymag"] = c.ymag;
    } else {
      j["yfov_degrees"] = glm::degrees(c.yfov);
    }
    out.push_back(j);
  }
  return out;
}

nlohmann::json describe(const Scene& scene) {
  using nlohmann::json;
  // Stored triangles by role; leaves and clusters of the distinct plants (each plant's ids
  // are its own).
  size_t role_tris[kRoleCount] = {};
  size_t leaf_count = 0, cluster_count = 0;
  for (size_t p = 0; p < scene.plant_count(); ++p) {
    std::set<uint32_t> leaves, clusters;
    for (uint32_t mi : plant_meshes(scene, p)) {
      const Mesh& m = scene.meshes[mi];
      for (size_t t = 0; t < m.triangle_count(); ++t) {
        ++role_tris[static_cast<int>(m.roles[t])];
        if (m.roles[t] == Role::Foliage) {
          leaves.insert(m.primitive_ids[t]);
          clusters.insert(m.cluster_ids[t]);
        }
      }
    }
    leaf_count += leaves.size();
    cluster_count += clusters.size();
  }
  json j;
  j["source"] = scene.report.source;
  j["triangles"] = scene.drawn_triangle_count();
  j["distinct_triangles"] = scene.triangle_count();
  j["instances"] = scene.instance_count();
  j["plants"] = scene.plant_count();
  j["vertices"] = scene.vertex_count();
  j["leaves"] = leaf_count;
  j["clusters"] = cluster_count;
  j["primitives"] = id_layout(scene).max_primitive;
  j["dropped_degenerate_triangles"] = scene.report.dropped_degenerate;
  json roles = json::object();
  for (int r = 0; r < kRoleCount; ++r)
    roles[role_name(static_cast<Role>(r))] = role_tris[r];
  j["triangles_by_role"] = roles;
  j["foliage"] = {{"rule", scene.report.foliage_rule}, {"reason", scene.report.foliage_reason}};
  j["cluster_method"] = scene.report.cluster_method;
  json meshes = json::array();
  for (const Mesh& m : scene.meshes)
    meshes.push_back({{"name", m.name},
                      {"triangles", m.triangle_count()},
                      {"vertices", m.positions.size()},
                      {"material", m.material},
                      {"role", m.roles.empty() ? "other" : role_name(m.roles[0])}});
  j["meshes"] = meshes;
  json mats = json::array();
  for (const Material& m : scene.materials)
    mats.push_back({{"name", m.name},
                    {"alpha_mode", alpha_mode_name(m.alpha_mode)},
                    {"alpha_cutoff", m.alpha_cutoff},
                    {"double_sided", m.double_sided},
                    {"textured", m.base_color_texture >= 0}});
  j["materials"] = mats;
  Bounds b = scene.bounds();
  j["bounds"] = {{"min", {b.min.x, b.min.y, b.min.z}},
                 {"max", {b.max.x, b.max.y, b.max.z}},
                 {"diagonal", b.diagonal()}};
  j["hierarchy_branches"] = scene.hierarchy.branch_parent.size();
  j["plant_list"] = describe_plants(scene);
  j["cameras"] = describe_cameras(scene);
  j["warnings"] = scene.report.warning_lines();
  return j;
}

void print_text(const nlohmann::json& j) {
  std::printf("source      %s\n", j["source"].get<std::string>().c_str());
  std::printf("triangles   %zu drawn, %zu distinct (vertices %zu, degenerate dropped %zu)\n",
              j["triangles"].get<size_t>(), j["distinct_triangles"].get<size_t>(),
              j["vertices"].get<size_t>(), j["dropped_degenerate_triangles"].get<size_t>());
  std::printf("plants      %zu distinct, %zu instances\n", j["plants"].get<size_t>(),
              j["instances"].get<size_t>());
  if (j["plants"].get<size_t>() > 1)
    for (auto& p : j["plant_list"])
      std::printf("plant       %s: %zu meshes, %zu triangles, %zu instances\n",
                  p["name"].get<std::string>().c_str(), p["meshes"].get<size_t>(),
                  p["triangles"].get<size_t>(), p["instances"].get<size_t>());
  std::printf("roles      ");
  for (auto& [k, v] : j["triangles_by_role"].items())
    std::printf(" %s %zu", k.c_str(), v.get<size_t>());
  std::printf(" (triangles)\n");
  std::printf("leaves      %zu in %zu clusters (%s)\n", j["leaves"].get<size_t>(),
              j["clusters"].get<size_t>(), j["cluster_method"].get<std::string>().c_str());
  std::printf("foliage     %s: %s\n", j["foliage"]["rule"].get<std::string>().c_str(),
              j["foliage"]["reason"].get<std::string>().c_str());
  for (auto& m : j["materials"])
    std::printf("material    %s (%s%s%s)\n", m["name"].get<std::string>().c_str(),
                m["alpha_mode"].get<std::string>().c_str(),
                m["double_sided"].get<bool>() ? ", double-sided" : "",
                m["textured"].get<bool>() ? ", textured" : "");
  for (auto& m : j["meshes"])
    std::printf("mesh        %s: %zu triangles, %s\n", m["name"].get<std::string>().c_str(),
                m["triangles"].get<size_t>(), m["role"].get<std::string>().c_str());
  auto& b = j["bounds"];
  std::printf("bounds      (%g, %g, %g) .. (%g, %g, %g), diagonal %g\n", b["min"][0].get<double>(),
              b["min"][1].get<double>(), b["min"][2].get<double>(), b["max"][0].get<double>(),
              b["max"][1].get<double>(), b["max"][2].get<double>(), b["diagonal"].get<double>());
  for (auto& c : j["cameras"]) {
    const bool ortho = c["type"] == "orthographic";
    std::printf("camera      %zu '%s': %s, %s %g, eye (%g, %g, %g), znear %g, zfar %g%s\n",
                c["index"].get<size_t>(), c["name"].get<std::string>().c_str(),
                c["type"].get<std::string>().c_str(), ortho ? "ymag" : "yfov",
                ortho ? c["ymag"].get<double>() : c["yfov_degrees"].get<double>(),
                c["eye"][0].get<double>(), c["eye"][1].get<double>(), c["eye"][2].get<double>(),
                c["znear"].get<double>(), c["zfar"].get<double>(),
                !ortho && c["zfar"].get<double>() == 0.0 ? " (infinite)" : "");
  }
  for (auto& w : j["warnings"])
    std::printf("warning     %s\n", w.get<std::string>().c_str());
}

// What `choice` starts, which backends are built, and the EGL devices.
nlohmann::json describe_gl(const GlChoice& choice) {
  const std::unique_ptr<GlContext> context = create_gl_context(choice);
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : gl_facts(*context))
    j[key] = value;
  j["software"] = context->info().software;
  std::vector<std::string> built;
  for (GlBackend b : built_gl_backends())
    built.push_back(gl_backend_name(b));
  j["built"] = built;
  j["egl_devices"] = egl_devices();
  return j;
}

void print_gl(const nlohmann::json& gl) {
  for (const char* key :
       {"backend", "device", "vendor", "renderer", "version", "platform", "fallback"})
    if (gl.contains(key)) std::printf("gl %-9s%s\n", key, gl[key].get<std::string>().c_str());
  std::string built;
  for (const auto& b : gl["built"])
    built += (built.empty() ? "" : ", ") + b.get<std::string>();
  std::printf("gl built    %s\n", built.c_str());
  for (const auto& d : gl["egl_devices"])
    std::printf("egl device  %s\n", d.get<std::string>().c_str());
}

}  // namespace

Action add_info_command(CLI::App& app) {
  struct Opts {
    SceneOptions scene;
    bool json = false;
    std::string gl;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Report triangles (drawn and distinct), instances, plants, leaves, clusters, roles, "
      "materials, bounds, cameras and what was detected");
  add_scene_options(*cmd, o->scene);
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  cmd->get_option("scene")->required(false);
  CLI::Option* gl =
      cmd->add_option("--gl", o->gl,
                      "Describe the GL backend BACKEND (auto, egl, egl:N, osmesa; without a "
                      "value: $SYLVA_GL, else auto) as the rendering commands would start it: "
                      "backend, device, vendor, renderer, version, why auto passed over EGL; "
                      "and the backends built and the EGL devices. The scene is then optional")
          ->expected(0, 1);
  return [o, gl] {
    if (!gl->count() && o->scene.path.empty())
      throw InputError("scene", "a scene file is required (or --gl)");
    // Checked before the scene is loaded.
    const GlChoice choice = gl->count() ? gl_choice_from_option(o->gl) : GlChoice{};
    nlohmann::json j = nlohmann::json::object();
    if (!o->scene.path.empty()) j = describe(load_scene_for_cli(o->scene, false));
    if (gl->count()) j["gl"] = describe_gl(choice);
    if (o->json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    if (!o->scene.path.empty()) print_text(j);
    if (gl->count()) print_gl(j["gl"]);
  };
}

}  // namespace sylva::cli
