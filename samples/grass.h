// A procedural grass patch (`sylva sample grass`) for Hegeman et al.'s grass visibility
// (Eq. 9): thin tapered blades standing on y = 0, each a quad from the root to mid-height
// and a triangle to the tip, leaning and curving a little, facing a random direction. The
// mesh and material are named "grass" and every triangle has Role::Grass, which survives a
// .glb round trip ("sylva_role": "grass"), so the renderer shades the blades by Eq. 9.
// Deterministic per seed (splitmix64, no standard-library distributions).
#pragma once

#include <cstdint>

#include "core/scene/scene.h"

namespace sylva {

// Valid blade counts (GrassOptions::blades).
constexpr int kMinGrassBlades = 1;
constexpr int kMaxGrassBlades = 200'000;

// Patch and blade sizes, scene units (metres).
inline constexpr float kGrassPatchSide = 1.0f;     // square patch, x and z in [-0.5, 0.5]
inline constexpr float kGrassHeight = 0.25f;       // tallest blade; each is 60-100% of it
inline constexpr float kGrassBladeWidth = 0.008f;  // at the root; tapering to a point

struct GrassOptions {
  uint64_t seed = 1;  // any value; the same seed gives the same bytes
  int blades = 2000;  // [1, 200'000]; the default renders in a fraction of a second
};

// One mesh "grass" (material "grass": opaque, double-sided, green): per blade 5 vertices and
// 3 triangles, primitive id = blade index + 1, cluster id 1, Role::Grass. Positions have
// y in [0, kGrassHeight], the lowest at exactly 0. Normals are unit, per vertex, across the
// blade (tilted up where the blade leans). Throws InputError("--blades", ...) when blades is
// outside [1, 200'000].
Scene make_grass(const GrassOptions& options);

}  // namespace sylva
