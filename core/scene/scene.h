// The scene model every other unit works on: meshes (each stored once), materials, textures,
// per-triangle primitive / cluster ids and roles, the optional plant hierarchy (branches with
// diameters, leaf -> branch), plants and their instances (a flat scene has none: its meshes
// are in world space), and what the loader decided and why.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sylva {

// What a triangle is. Foliage is what the Luft preprocessing and the blob/watercolor
// layers work on; wood, ground and other geometry receive the crown's occlusion (Hegeman et
// al. Eq. 7-8); grass blades see the sky by their height (Eq. 9) times that occlusion.
enum class Role : uint8_t { Foliage = 0, Wood = 1, Ground = 2, Other = 3, Grass = 4 };
inline constexpr int kRoleCount = 5;
const char* role_name(Role r);

enum class AlphaMode : uint8_t { Opaque = 0, Mask = 1, Blend = 2 };
const char* alpha_mode_name(AlphaMode m);

// 8-bit RGBA image, rows top to bottom (as stored in PNG/JPEG), sRGB-encoded colour.
struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
};

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};   // linear RGBA factor (glTF baseColorFactor)
  int base_color_texture = -1;  // index into Scene::textures, -1 = none
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;  // [0, 1]; used with AlphaMode::Mask
  bool double_sided = false;
};

// One triangle mesh, in world space (flat scene) or in its plant's space. Vertex arrays are
// parallel; optional ones are empty.
// Per-triangle arrays have indices.size() / 3 entries.
struct Mesh {
  std::string name;
  int material = -1;                 // index into Scene::materials, -1 = default grey
  std::vector<glm::vec3> positions;  // scene units
  std::vector<glm::vec3> normals;    // unit length unless an ambient
                                     // coefficient is encoded in the length (Luft et al.)
  std::vector<glm::vec2> uvs;        // optional, glTF convention (v down)
  std::vector<glm::vec4> colors;     // optional linear RGBA vertex colours
  std::vector<float> ka;             // optional ambient coefficient in [0, 1] per vertex; when
                                     // present the renderer uses it, not the normal length
  std::vector<uint32_t> indices;     // 3 per triangle
  // The foliage normals already face out of the crown on both sides of a leaf (realigned by
  // Luft et al. §3.3, e.g. read from a baked file): the renderer never flips them on back faces.
  bool outward_normals = false;

  // Per triangle. Ids are 1-based (0 means background in ID buffers).
  std::vector<uint32_t> primitive_ids;  // connected component (a leaf), unique in the scene
  std::vector<uint32_t> cluster_ids;    // leaf group; all non-foliage shares one cluster
  std::vector<Role> roles;

  size_t triangle_count() const { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float diagonal() const { return empty() ? 0.0f : glm::length(max - min); }
};

// A sphere holding the scene; the camera frames it, so the framing does not change as the
// view turns (turntables keep their scale).
struct Sphere {
  glm::vec3 centre{0.0f};
  float radius = -1.0f;  // < 0: empty
  bool empty() const { return radius < 0.0f; }
};

// Plant structure as written by `sylva sample` (glTF extras "sylva_hierarchy"): branches
// with their parent and diameter, and for each leaf (foliage primitive, in primitive-id
// order) the branch carrying it. Empty when the model does not carry it.
struct Hierarchy {
  std::vector<int32_t> branch_parent;  // -1 for the trunk root
  std::vector<float> branch_diameter;  // scene units
  std::vector<int32_t> leaf_branch;    // per leaf, index into the branch arrays
  bool empty() const { return branch_parent.empty(); }
};

// What loading and classification decided, for `sylva info`.
struct SceneReport {
  std::string source;          // file path or "sample:tree"
  std::string foliage_rule;    // e.g. "name match", "alpha MASK", "--foliage all"
  std::string foliage_reason;  // one line: which materials/meshes and why
  std::string cluster_method;  // "hierarchy (division diameter 0.05)" or "k-means (k=12, seed 1)"
  size_t dropped_degenerate = 0;      // zero-area / repeated-index triangles removed on load
  std::vector<std::string> warnings;  // the first of each kind, one line each

  // Keeps `text` if it is the first warning of its `kind` (e.g. "points/lines"); later ones of
  // that kind are only counted, so a hostile file with 100,000 bad meshes gives one line.
  void warn(const std::string& kind, const std::string& text);
  // `warnings`, each followed by "(and N more like it)" when its kind repeated.
  std::vector<std::string> warning_lines() const;

 private:
  struct Kind {
    std::string name;
    size_t line;     // its first warning's index in `warnings`
    size_t repeats;  // warnings of this kind after the first
  };
  std::vector<Kind> m_kinds;
};

// A distinct mesh group stored once, in its own space (plant space): in glTF a node subtree
// that occurs more than once or is marked "sylva_plant", or a mesh drawn with
// EXT_mesh_gpu_instancing (core/scene/gltf_read.h). Every per-plant computation (the Luft
// preprocessing, leaf clusters, their cache) runs on it alone (core/scene/instances.h).
struct Plant {
  std::string name;              // its root node's name, else its first mesh's
  std::vector<uint32_t> meshes;  // indices into Scene::meshes, ascending
  Hierarchy hierarchy;           // its own (the root node's extras "sylva_hierarchy")
};

// One placement of a plant: drawn with the plant's meshes moved by `transform`.
struct Instance {
  uint32_t plant = 0;         // index into Scene::plants
  glm::mat4 transform{1.0f};  // plant space -> world space; finite, invertible
  std::string name;           // the node's name ("" = none)
};

// A camera stored in the file (glTF: a camera placed by a node). Looks down its -Z with +Y
// up; the image's aspect ratio replaces the file's.
struct SceneCamera {
  std::string name;  // the node's name, else the camera's, else "camera <i>"
  bool orthographic = false;
  float yfov = 0.0f;               // perspective: vertical field of view, radians, (0, pi)
  float aspect = 0.0f;             // perspective: the file's aspect ratio, 0 = none given
  float xmag = 0.0f, ymag = 0.0f;  // orthographic: half width and height, scene units, > 0
  float znear = 0.0f;              // scene units: > 0 (perspective), >= 0 (orthographic)
  float zfar = 0.0f;               // > znear; 0 = infinite (perspective only)
  glm::mat4 to_world{1.0f};        // camera space -> world, rigid (scale removed)
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  Hierarchy hierarchy;  // a flat scene's (an instanced scene's plants carry their own)
  SceneReport report;
  // Instancing. Both empty: a flat scene, every mesh in world space and drawn once (one
  // implicit plant holding every mesh, one instance at the identity). Otherwise every mesh
  // belongs to exactly one plant and is drawn once per instance of it.
  std::vector<Plant> plants;
  std::vector<Instance> instances;
  std::vector<SceneCamera> cameras;  // in the file's node order

  bool instanced() const { return !plants.empty(); }
  size_t plant_count() const { return instanced() ? plants.size() : 1; }
  size_t instance_count() const { return instanced() ? instances.size() : 1; }
  // Triangles drawn: each mesh's count times its plant's instances (= triangle_count() for
  // a flat scene).
  size_t drawn_triangle_count() const;

  // World space: over every instance.
  Bounds bounds() const;
  Bounds bounds(Role role) const;         // bounds of the triangles with this role
  Bounds bounds_except(Role role) const;  // of every other triangle (and those with no role)
  // Centred on the bounds' centre, radius = farthest used vertex: never larger than the box's
  // circumscribed sphere and, for a tall tree, noticeably tighter. Ground triangles
  // (Role::Ground) are left out when there is anything else, so a ground plane (e.g.
  // `--ground`, a few times the plant's size) does not shrink the plant in the frame.
  Sphere framing_sphere() const;
  size_t triangle_count() const;  // stored (distinct) triangles
  size_t vertex_count() const;    // stored vertices
  // Over the stored meshes: each plant's own ids (an instance's ids in the id buffer are
  // these plus its bases, core/scene/instances.h).
  uint32_t max_primitive_id() const;
  uint32_t max_cluster_id() const;
  // The cluster id all non-foliage triangles share (trunk and branches), 0 when there are none;
  // in an instanced scene, the one id they have in the id buffer (IdLayout::branch_cluster).
  uint32_t branch_cluster_id() const;
};

}  // namespace sylva
