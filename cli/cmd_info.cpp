// sylva info SCENE [--json]: what the scene holds and what the loader decided.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "cli/commands.h"
#include "cli/common_options.h"

namespace sylva::cli {

namespace {

nlohmann::json describe(const Scene& scene) {
  using nlohmann::json;
  size_t role_tris[kRoleCount] = {};
  std::set<uint32_t> leaves, clusters;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      ++role_tris[static_cast<int>(m.roles[t])];
      if (m.roles[t] == Role::Foliage) {
        leaves.insert(m.primitive_ids[t]);
        clusters.insert(m.cluster_ids[t]);
      }
    }
  json j;
  j["source"] = scene.report.source;
  j["triangles"] = scene.triangle_count();
  j["vertices"] = scene.vertex_count();
  j["leaves"] = leaves.size();
  j["clusters"] = clusters.size();
  j["primitives"] = scene.max_primitive_id();
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
  j["warnings"] = scene.report.warning_lines();
  return j;
}

void print_text(const nlohmann::json& j) {
  std::printf("source      %s\n", j["source"].get<std::string>().c_str());
  std::printf("triangles   %zu (vertices %zu, degenerate dropped %zu)\n",
              j["triangles"].get<size_t>(), j["vertices"].get<size_t>(),
              j["dropped_degenerate_triangles"].get<size_t>());
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
      "info", "Report triangles, leaves, clusters, roles, materials, bounds and what was detected");
  add_scene_options(*cmd, o->scene);
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  return [o] {
    Scene scene = load_scene_for_cli(o->scene, false);
    nlohmann::json j = describe(scene);
    if (o->json)
      std::cout << j.dump(2) << "\n";
    else
      print_text(j);
  };
}

}  // namespace sylva::cli
