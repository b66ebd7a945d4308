// sylva info SCENE [--json]: what the scene holds (triangles drawn and distinct, instances,
// plants, cameras, ...) and what the loader decided (core/scene/scene_info.h), as JSON or text.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/common_options.h"
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

}  // namespace

Action add_info_command(CLI::App& app) {
  struct Opts {
    SceneOptions scene;
    bool json = false;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Report triangles (drawn and distinct), instances, plants, leaves, clusters, roles, "
      "materials, bounds, cameras and what was detected");
  add_scene_options(*cmd, o->scene);
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  return [o] {
    const Scene scene = load_scene_for_cli(o->scene, false);
    const std::string json = scene_info_json(scene);
    if (o->json)
      std::cout << json << "\n";
    else
      print_text(nlohmann::json::parse(json));
  };
}

}  // namespace sylva::cli
