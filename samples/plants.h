// Procedural sample plants from an L-system (after the tree file in Dudley's thesis,
// appendix A.2): branches as tapered cylinders with diameters, leaves as separate small
// quads (single-sided, drawn double-sided), hierarchy recorded (leaf -> branch -> diameter).
// Deterministic per seed.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene/scene.h"

namespace sylva {

enum class PlantKind { Tree, Bush, Conifer };

// Valid leaf counts (PlantOptions::leaves other than 0).
constexpr int kMinPlantLeaves = 100;
constexpr int kMaxPlantLeaves = 2'000'000;

struct PlantOptions {
  PlantKind kind = PlantKind::Tree;
  uint64_t seed = 1;  // any value; the same seed gives the same bytes
  int leaves = 0;     // target leaf count; 0 = the kind's default; valid [100, 2'000'000]
};

// Parses "tree" | "bush" | "conifer"; throws InputError("--kind"...) otherwise.
PlantKind parse_plant_kind(const std::string& s);
const char* plant_kind_name(PlantKind k);
// The leaf count used for leaves = 0: tree 10'000, bush 5'000, conifer 20'000.
int plant_default_leaves(PlantKind kind);

// Returns a scene with roles, primitive ids (one per leaf, one per branch segment chain),
// hierarchy, materials ("leaves" with a generated leaf texture, alpha MASK, double-sided;
// "bark") set. Cluster ids are left at 1 for npr::assign_clusters.
//
// Layout: meshes[0] "leaves" (one quad per leaf, 4 unique vertices, primitive ids 1..L in
// mesh order), meshes[1] "bark" (one tapered tube per branch axis, primitive ids L+1.. in
// branch order, which is exactly the connected-component numbering of the loader).
// hierarchy.branch_* are indexed like the bark tubes; leaf_branch follows leaf order.
// Exactly `leaves` leaves; plant size is fixed per kind (tree ~7 m, bush ~1.6 m, conifer
// ~9 m tall, base at y = 0 around x = z = 0), so leaves shrink as 1/sqrt(leaves).
// Throws InputError("--leaves", ...) when leaves is outside [100, 2'000'000] (0 = default).
Scene make_plant(const PlantOptions& options);

}  // namespace sylva
