// sylva info SCENE [--json]: what the scene holds (triangles drawn and distinct, instances,
// plants, cameras, ...) and what the loader decided (core/scene/scene_info.h), as JSON or text.
// sylva info --gl [BACKEND]: the GL backend a rendering command would take (backend, device,
// vendor, renderer, version), the backends built and the EGL devices; the scene is then optional.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/gl/gl_context.h"
#include "core/scene/scene_info.h"

namespace sylva::cli {

namespace {

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
    if (!o->scene.path.empty())
      j = nlohmann::json::parse(scene_info_json(load_scene_for_cli(o->scene, false)));
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
