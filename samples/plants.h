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

struct PlantOptions {
  PlantKind kind = PlantKind::Tree;
  uint64_t seed = 1;
  int leaves = 0;  // target leaf count; 0 = the kind's default; valid [100, 2'000'000]
};

// Parses "tree" | "bush" | "conifer"; throws InputError("--kind"...) otherwise.
PlantKind parse_plant_kind(const std::string& s);
const char* plant_kind_name(PlantKind k);

// Returns a scene with roles, primitive ids (one per leaf, one per branch segment chain),
// hierarchy, materials ("leaves" with a generated leaf texture, alpha MASK, double-sided;
// "bark") set. Cluster ids are left at 1 for npr::assign_clusters.
Scene make_plant(const PlantOptions& options);

}  // namespace sylva
