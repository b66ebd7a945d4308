#include "core/scene/instances.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace sylva {

namespace {

// The largest ids one instance of plant p adds: primitive, foliage cluster, object.
struct PlantIdSpan {
  uint64_t primitive = 0, cluster = 0, object = 0;
  bool non_foliage = false;
};

PlantIdSpan plant_span(const Scene& scene, size_t p) {
  PlantIdSpan s;
  const std::vector<uint32_t> meshes = plant_meshes(scene, p);
  s.object = meshes.size();
  for (uint32_t mi : meshes) {
    const Mesh& m = scene.meshes[mi];
    for (uint32_t id : m.primitive_ids)
      s.primitive = std::max<uint64_t>(s.primitive, id);
    for (size_t t = 0; t < m.cluster_ids.size(); ++t) {
      const bool foliage = t < m.roles.size() && m.roles[t] == Role::Foliage;
      if (foliage)
        s.cluster = std::max<uint64_t>(s.cluster, m.cluster_ids[t]);
      else
        s.non_foliage = true;
    }
  }
  return s;
}

uint32_t checked(uint64_t v, const char* what) {
  if (v > std::numeric_limits<uint32_t>::max())
    throw InputError("scene", std::string("too many instances: their ") + what +
                                  " ids pass 2^32 - 1, the id buffer's limit");
  return uint32_t(v);
}

}  // namespace

std::vector<uint32_t> plant_meshes(const Scene& scene, size_t plant) {
  if (scene.instanced()) return scene.plants[plant].meshes;
  std::vector<uint32_t> all(scene.meshes.size());
  for (size_t m = 0; m < all.size(); ++m)
    all[m] = uint32_t(m);
  return all;
}

std::vector<uint32_t> plant_instances(const Scene& scene, size_t plant) {
  if (!scene.instanced()) return {0};
  std::vector<uint32_t> out;
  for (size_t i = 0; i < scene.instances.size(); ++i)
    if (scene.instances[i].plant == plant) out.push_back(uint32_t(i));
  return out;
}

IdLayout id_layout(const Scene& scene) {
  IdLayout l;
  if (!scene.instanced()) {
    l.bases.resize(1);
    l.max_primitive = scene.max_primitive_id();
    l.max_cluster = scene.max_cluster_id();
    l.max_object = uint32_t(scene.meshes.size());
    return l;
  }
  std::vector<PlantIdSpan> spans;
  for (size_t p = 0; p < scene.plants.size(); ++p)
    spans.push_back(plant_span(scene, p));
  uint64_t primitive = 0, cluster = 0, object = 0;
  bool non_foliage = false;
  for (const Instance& inst : scene.instances) {
    l.bases.push_back(
        {checked(primitive, "primitive"), checked(cluster, "cluster"), checked(object, "object")});
    const PlantIdSpan& s = spans[inst.plant];
    primitive += s.primitive;
    cluster += s.cluster;
    object += s.object;
    non_foliage = non_foliage || s.non_foliage;
  }
  l.max_primitive = checked(primitive, "primitive");
  l.max_object = checked(object, "object");
  l.branch_cluster = non_foliage ? checked(cluster + 1, "cluster") : 0;
  l.max_cluster = non_foliage ? l.branch_cluster : checked(cluster, "cluster");
  return l;
}

Scene plant_scene(const Scene& scene, size_t plant, bool textures) {
  Scene s;
  for (uint32_t mi : plant_meshes(scene, plant))
    s.meshes.push_back(scene.meshes[mi]);
  s.materials = scene.materials;
  if (textures) s.textures = scene.textures;
  s.hierarchy = scene.instanced() ? scene.plants[plant].hierarchy : scene.hierarchy;
  s.report.source = scene.report.source;
  return s;
}

glm::mat3 normal_matrix(const glm::mat4& transform) {
  return glm::mat3(glm::transpose(glm::inverse(glm::dmat3(glm::dmat4(transform)))));
}

namespace {

// One instance's copy of `mesh` in world space with the id buffer's ids.
Mesh world_mesh(const Mesh& mesh, const Instance& inst, const InstanceIdBase& base,
                uint32_t branch_cluster) {
  Mesh m = mesh;
  if (!inst.name.empty()) m.name = inst.name + "/" + mesh.name;
  const glm::dmat4 t(inst.transform);
  for (glm::vec3& p : m.positions)
    p = glm::vec3(t * glm::dvec4(p, 1.0));
  const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(t)));
  for (glm::vec3& n : m.normals) {
    // The length carries ka when the normals encode it (Luft et al.): keep it.
    const double len = glm::length(glm::dvec3(n));
    const glm::dvec3 w = nm * glm::dvec3(n);
    const double wl = glm::length(w);
    n = wl > 0.0 && std::isfinite(wl) ? glm::vec3(w / wl * len) : n;
  }
  if (glm::determinant(glm::dmat3(t)) < 0.0)
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
      std::swap(m.indices[i + 1], m.indices[i + 2]);
  for (uint32_t& id : m.primitive_ids)
    id += base.primitive;
  for (size_t k = 0; k < m.cluster_ids.size(); ++k) {
    const bool foliage = k < m.roles.size() && m.roles[k] == Role::Foliage;
    m.cluster_ids[k] =
        foliage || branch_cluster == 0 ? m.cluster_ids[k] + base.cluster : branch_cluster;
  }
  return m;
}

}  // namespace

Scene flatten(const Scene& scene) {
  if (!scene.instanced()) return scene;
  const IdLayout ids = id_layout(scene);
  Scene out;
  out.materials = scene.materials;
  out.textures = scene.textures;
  out.report = scene.report;
  if (scene.instances.size() == 1) out.hierarchy = scene.plants[scene.instances[0].plant].hierarchy;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    for (uint32_t mi : scene.plants[inst.plant].meshes)
      out.meshes.push_back(world_mesh(scene.meshes[mi], inst, ids.bases[i], ids.branch_cluster));
  }
  return out;
}

void validate_instances(const Scene& scene, const std::string& where) {
  if (!scene.instanced()) {
    if (!scene.instances.empty())
      throw InputError(where, "instances without plants (a flat scene has neither)");
    return;
  }
  std::vector<int> owner(scene.meshes.size(), -1);
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const Plant& plant = scene.plants[p];
    const std::string name = "plant " + std::to_string(p) + " '" + plant.name + "'";
    if (plant.meshes.empty()) throw InputError(where, name + " has no meshes");
    for (size_t k = 0; k < plant.meshes.size(); ++k) {
      const uint32_t m = plant.meshes[k];
      if (m >= scene.meshes.size() || (k > 0 && m <= plant.meshes[k - 1]))
        throw InputError(where, name + ": mesh list not ascending within the scene's meshes");
      if (owner[m] != -1)
        throw InputError(where, "mesh " + std::to_string(m) + " belongs to two plants");
      owner[m] = int(p);
    }
  }
  for (size_t m = 0; m < owner.size(); ++m)
    if (owner[m] == -1) throw InputError(where, "mesh " + std::to_string(m) + " is in no plant");
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const std::string name = "instance " + std::to_string(i) + " '" + inst.name + "'";
    if (inst.plant >= scene.plants.size())
      throw InputError(where, name + " refers to a missing plant");
    double scale = 0.0;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        const float v = inst.transform[c][r];
        if (!std::isfinite(v)) throw InputError(where, name + ": transform is not finite");
        if (c < 3 && r < 3) scale = std::max(scale, double(std::abs(v)));
      }
    const double det = glm::determinant(glm::dmat3(glm::dmat4(inst.transform)));
    if (!(std::abs(det) >= 1e-12 * scale * scale * scale) || scale == 0.0)
      throw InputError(where, name + ": transform is singular (a zero scale)");
  }
}

void remove_meshes(Scene& scene, const std::vector<char>& keep) {
  std::vector<uint32_t> new_index(scene.meshes.size(), 0);
  size_t out = 0;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    new_index[m] = uint32_t(out);
    if (!keep[m]) continue;
    if (out != m) scene.meshes[out] = std::move(scene.meshes[m]);
    ++out;
  }
  scene.meshes.resize(out);
  if (!scene.instanced()) return;
  std::vector<int> new_plant(scene.plants.size(), -1);
  std::vector<Plant> plants;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    Plant& plant = scene.plants[p];
    std::erase_if(plant.meshes, [&](uint32_t m) { return !keep[m]; });
    for (uint32_t& m : plant.meshes)
      m = new_index[m];
    if (plant.meshes.empty()) continue;
    new_plant[p] = int(plants.size());
    plants.push_back(std::move(plant));
  }
  scene.plants = std::move(plants);
  std::erase_if(scene.instances, [&](const Instance& i) { return new_plant[i.plant] < 0; });
  for (Instance& i : scene.instances)
    i.plant = uint32_t(new_plant[i.plant]);
}

}  // namespace sylva
