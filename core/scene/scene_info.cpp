#include "core/scene/scene_info.h"

#include <nlohmann/json.hpp>
#include <set>

#include "core/scene/instances.h"

namespace sylva {

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

}  // namespace

std::string scene_info_json(const Scene& scene) {
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
  return j.dump(2);
}

}  // namespace sylva
