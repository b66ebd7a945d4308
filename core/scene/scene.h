// The scene model every other unit works on: flattened meshes (node transforms applied),
// materials, textures, per-triangle primitive / cluster ids and roles, the optional plant
// hierarchy (branches with diameters, leaf -> branch), and what the loader decided and why.
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

// One triangle mesh in world space. Vertex arrays are parallel; optional ones are empty.
// Per-triangle arrays have indices.size() / 3 entries.
struct Mesh {
  std::string name;
  int material = -1;                 // index into Scene::materials, -1 = default grey
  std::vector<glm::vec3> positions;  // world space (scene units)
  std::vector<glm::vec3> normals;    // world space; unit length unless an ambient
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

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  Hierarchy hierarchy;
  SceneReport report;

  Bounds bounds() const;
  Bounds bounds(Role role) const;  // bounds of the triangles with this role
  // Centred on the bounds' centre, radius = farthest used vertex: never larger than the box's
  // circumscribed sphere and, for a tall tree, noticeably tighter. Ground triangles
  // (Role::Ground) are left out when there is anything else, so a ground plane (e.g.
  // `--ground`, a few times the plant's size) does not shrink the plant in the frame.
  Sphere framing_sphere() const;
  size_t triangle_count() const;
  size_t vertex_count() const;
  uint32_t max_primitive_id() const;
  uint32_t max_cluster_id() const;
  // The cluster id all non-foliage triangles share (trunk and branches), 0 when there are none.
  uint32_t branch_cluster_id() const;
};

}  // namespace sylva
