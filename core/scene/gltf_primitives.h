// Reading one glTF mesh's triangle primitives in the mesh's own space (used by gltf_read.cpp,
// which places them once per node, or once per plant, that uses the mesh): POSITION, NORMAL
// (as stored), TEXCOORD_0, COLOR_0 (COLOR_1 in baked files, gltf_write.h), _AMBIENT, indices
// triangulated from triangles, strips and fans, the material, roles from "sylva_role" extras
// and the "sylva_normals" marker. Points and lines are skipped with a warning; malformed data
// throws InputError(path, "mesh '<name>': ...").
#pragma once

#include <tiny_gltf.h>

#include <glm/glm.hpp>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

#include "core/scene/gltf_accessor.h"
#include "core/scene/scene.h"

namespace sylva {

// The raw JSON at a path of keys and array indices, or null.
const nlohmann::json* json_at(const nlohmann::json& root,
                              std::initializer_list<std::variant<const char*, size_t>> keys);

// A primitive as stored: Mesh::positions and Mesh::normals in mesh space (normals not
// normalised; empty when the file has none), Mesh::name the primitive's "[k]" suffix when its
// mesh has several ("" otherwise).
struct LocalPrimitive {
  Mesh mesh;
};

class GltfPrimitiveReader {
 public:
  // `report` receives the warnings; `material_count` bounds the material indices.
  GltfPrimitiveReader(const std::string& path, const tinygltf::Model& model,
                      const nlohmann::json& json, const GltfAccessorReader& accessors,
                      size_t material_count, SceneReport& report);

  // The primitives of glTF mesh `mesh` (read once, then remembered); `node_name` names an
  // unnamed mesh in messages.
  const std::vector<LocalPrimitive>& read(int mesh, const std::string& node_name);
  // A placed primitive's name: the mesh's, else the node's, else "mesh<i>", with its suffix.
  std::string name(int mesh, const std::string& node_name, const LocalPrimitive& p) const;

 private:
  const std::string& m_path;
  const tinygltf::Model& m_model;
  const nlohmann::json& m_json;
  const GltfAccessorReader& m_accessors;
  size_t m_material_count;
  SceneReport& m_report;
  std::map<int, std::vector<LocalPrimitive>> m_read;
};

// The primitive moved by `transform`: positions in double, normals by the inverse transpose
// (unit length; area-weighted ones when the primitive has none), triangles reversed when the
// transform mirrors.
Mesh place_primitive(const LocalPrimitive& p, const glm::dmat4& transform, std::string name);

}  // namespace sylva
