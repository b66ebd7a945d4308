#include "cli/cryptomatte_render.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"
#include "core/scene/instances.h"

namespace sylva::cli {

std::vector<std::string> parse_cryptomatte_list(const std::string& list) {
  if (list == "none") return {};
  std::vector<std::string> kinds;
  std::stringstream ss(list);
  for (std::string kind; std::getline(ss, kind, ',');) {
    if (kind != "object" && kind != "material" && kind != "asset")
      throw InputError("--cryptomatte",
                       "unknown kind '" + kind + "' (allowed: object, material, asset, or none)");
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) kinds.push_back(kind);
  }
  if (kinds.empty()) throw InputError("--cryptomatte", "name a kind, or none");
  return kinds;
}

namespace {

std::string mesh_name(const Scene& scene, size_t i) {
  return scene.meshes[i].name.empty() ? "mesh_" + std::to_string(i) : scene.meshes[i].name;
}

// Object ids in id order (core/scene/instances.h): a flat scene's meshes; an instanced
// scene's instances, each with its plant's meshes, named "<instance>/<mesh>".
std::vector<std::string> object_names(const Scene& scene) {
  std::vector<std::string> names;
  if (!scene.instanced()) {
    for (size_t i = 0; i < scene.meshes.size(); ++i)
      names.push_back(mesh_name(scene, i));
    return names;
  }
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& inst = scene.instances[i];
    const std::string prefix = inst.name.empty() ? "instance_" + std::to_string(i) : inst.name;
    for (uint32_t m : scene.plants[inst.plant].meshes)
      names.push_back(prefix + "/" + mesh_name(scene, m));
  }
  return names;
}

// Material ids: index + 1, and the default grey after the scene's materials.
std::vector<std::string> material_names(const Scene& scene) {
  std::vector<std::string> names;
  for (size_t i = 0; i < scene.materials.size(); ++i)
    names.push_back(scene.materials[i].name.empty() ? "material_" + std::to_string(i)
                                                    : scene.materials[i].name);
  names.push_back("default");
  return names;
}

std::vector<std::string> cluster_names(const Scene& scene) {
  const uint32_t most = id_layout(scene).max_cluster;
  std::vector<std::string> names;
  for (uint32_t id = 1; id <= most; ++id)
    names.push_back("cluster_" + std::to_string(id));
  return names;
}

}  // namespace

std::vector<CryptomatteImage> render_cryptomattes(Frame& frame,
                                                  const std::vector<std::string>& kinds) {
  std::vector<CryptomatteImage> out;
  for (const std::string& kind : kinds) {
    RasterRequest request = frame.setup.request;
    request.targets = static_cast<TargetMask>(Target::Id);
    request.id_samples = true;
    CryptomatteImage image;
    if (kind == "object") {
      request.id_kind = IdKind::Object;
      image.layer = {"CryptoObject", object_names(frame.scene)};
    } else if (kind == "material") {
      request.id_kind = IdKind::Material;
      image.layer = {"CryptoMaterial", material_names(frame.scene)};
    } else {
      request.id_kind = IdKind::Cluster;
      image.layer = {"CryptoAsset", cluster_names(frame.scene)};
    }
    image.samples =
        frame.rasterizer->render(frame.setup.camera, frame.setup.lighting, request).id_samples;
    image.factor = request.ssaa;
    out.push_back(std::move(image));
  }
  return out;
}

}  // namespace sylva::cli
