// A small procedural bracketed L-system for plant skeletons (after Dudley's tree file,
// appendix A.2): a 3D turtle (F, + -, & ^, \ /, [ ] by value copies) records internodes
// grouped into branch axes; growth rules (samples/plants.cpp) are recursive functions of
// an apex age t, the way L-studio's decomposition rules are. Randomness is keyed: each
// apex carries a 64-bit key and every random choice is a hash of (key, purpose), so the
// same seed gives the same plant bit for bit on every standard library, and a node's
// choices do not depend on how many other nodes exist. The interpretation step turns the
// skeleton into bark tubes (pipe-model diameters) and leaf quads.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/scene.h"

namespace sylva {

// splitmix64-style mixing of a key with a salt; the building block of keyed randomness.
uint64_t mix_key(uint64_t key, uint64_t salt);
// Uniform in [0, 1) with 24-bit resolution, from a key.
float key_unit(uint64_t key);
// Uniform in [-1, 1), from a key.
inline float key_signed(uint64_t key) {
  return 2.0f * key_unit(key) - 1.0f;
}

// The turtle state (ABOP): position and an orthonormal frame. Angles in radians.
struct Turtle {
  glm::vec3 pos{0.0f};
  glm::vec3 heading{0.0f, 1.0f, 0.0f};  // H, the growth direction
  glm::vec3 left{-1.0f, 0.0f, 0.0f};    // L
  glm::vec3 up{0.0f, 0.0f, 1.0f};       // U = H x L

  void turn(float a);   // '+' (a > 0) / '-' : rotate about U
  void pitch(float a);  // '&' (a > 0, pitch down) / '^' : rotate about L
  void roll(float a);   // '/' (a > 0, roll right) / '\' : rotate about H
  // Tropism: bends H towards `dir` by up to `weight` (0 = none, 1 = fully), keeping the
  // frame orthonormal with minimal twist.
  void bend_towards(const glm::vec3& dir, float weight);
};

// One F: a straight internode between two nodes of one branch axis.
struct Internode {
  glm::vec3 start{0.0f};
  glm::vec3 end{0.0f};
  glm::vec3 up{0.0f, 0.0f, 1.0f};  // turtle U at the node (reference for leaf rolls)
  float age = 0;                   // apex age t when produced (L-system time units)
  int32_t branch = 0;              // index into Skeleton::branches
  int32_t leaf_count = 0;          // leaves carried, in pairs (set by the plant after fitting)
  bool leafy = false;              // may carry leaves (young shoot)
  uint64_t key = 0;                // random key for the leaves on this internode

  glm::vec3 heading() const { return glm::normalize(end - start); }
  float length() const { return glm::length(end - start); }
};

// A branch axis: a chain of internodes sharing nodes (end of one = start of the next),
// attached at the end node of internode `parent_internode` of branch `parent`.
struct Branch {
  int32_t parent = -1;
  int32_t parent_internode = -1;  // global internode index, -1 for the root
  int32_t first = 0;              // first internode (global index); internodes contiguous
  int32_t count = 0;
  int32_t order = 0;  // 0 = trunk / root, +1 per lateral
};

// Internodes grouped into branches. Grow one axis completely (begin, forward..., end)
// before starting its laterals, so each branch's internodes are contiguous and parents
// come before children.
class Skeleton {
 public:
  // `budget`: maximum internodes; beyond it forward() is ignored and overflow() is true.
  explicit Skeleton(size_t budget = SIZE_MAX) : m_budget(budget) {}

  int32_t begin_branch(int32_t parent, int32_t parent_internode, int32_t order);
  // F(length): moves the turtle, records an internode on the current branch.
  void forward(Turtle& t, float length, float age, bool leafy, uint64_t key);
  // Closes the current branch; drops it and returns -1 if it has no internodes.
  int32_t end_branch();

  bool overflow() const { return m_overflow; }
  size_t leafy_count() const { return m_leafy; }
  // Scales all positions about the origin (after growth, to normalise plant size).
  void scale(float s);
  Bounds bounds() const;

  std::vector<Branch> branches;
  std::vector<Internode> internodes;

 private:
  size_t m_budget;
  size_t m_leafy = 0;
  bool m_overflow = false;
};

// Pipe model: leaves carried by each internode (its own plus everything distal), and the
// diameter at its start node, `root_diameter * sqrt(carried / total)` clamped below by
// `min_diameter` (scene units, > 0). Non-increasing from parent to child by construction.
std::vector<float> pipe_diameters(const Skeleton& s, float root_diameter, float min_diameter);

// How leaves are placed and shaped on leafy internodes (Dudley A.2: pairs rolled 180°,
// successive pairs rolled 90°, pitched Down(45 + 30 t/D) from the axis).
struct LeafStyle {
  float length = 0.2f;        // scene units, > 0; blade quad length incl. petiole
  float aspect = 0.6f;        // quad width / length, (0, 1]
  float angle_young = 45.0f;  // degrees from the axis at age 0, [0, 90]
  float angle_old = 75.0f;    // degrees from the axis at age max_age, [0, 90]
  float max_age = 10.0f;      // age at which angle_old applies (the D of A.2), > 0
  float face_up = 0.5f;       // [0, 1]: how far blades turn their face towards +y
  float jitter = 0.15f;       // [0, 0.5]: relative size jitter; angles jitter ~60° * it
};

// Appends one quad (4 unique vertices, 2 triangles, normals = blade normal, UVs covering
// the texture with the petiole at v = 1) per leaf to `leaves`; leaves in internode order,
// pairs along each internode. `leaf_branch` receives the branch of each leaf. Jitter from
// std::mt19937_64(seed).
void emit_leaves(const Skeleton& s, const LeafStyle& style, uint64_t seed, Mesh& leaves,
                 std::vector<int32_t>& leaf_branch);

// Appends one tapered tube per branch (branch order; one connected component each): 8
// sides where the branch base diameter >= `thick_diameter` (scene units), else 6; smooth
// radial normals, UVs u around (seam duplicated), v along (1 per circumference of the
// base); the tip closed by a short cone, the base open. Ring diameters from `diameters`
// (pipe_diameters), the tip ring at 60% of the last. Appends per-triangle primitive ids:
// branch k (k-th non-empty branch) gets `first_id + k`.
void emit_bark(const Skeleton& s, const std::vector<float>& diameters, float thick_diameter,
               uint32_t first_id, Mesh& bark);

}  // namespace sylva
