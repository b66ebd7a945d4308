// Levels of detail of a plant (core/gl/rasterizer.h draws an instance with the level its
// projected size asks for): level l keeps about half of level l - 1's triangles. Small
// foliage parts (connected components of at most kLodLeafTriangles triangles: leaf cards,
// needles) are pruned as in Cook, Halstead, Planck & Ebert 2007 ("Stochastic simplification
// of aggregate detail"): a seeded half of them is kept per level and each kept one is
// enlarged about its centroid by sqrt(2) (twice its area), so the crown covers about the same
// pixels. Everything else (wood, large fronds) is cut in connected pieces, and a level keeps
// the largest pieces (by bounding-box diagonal) that fit in half the triangles of the level
// before, so twigs go first and the trunk and main branches stay; when the largest piece alone
// is more, it is decimated with OpenMesh's quadric decimater (halfedge collapses, so every
// remaining vertex is one of the mesh's own). Each level
// vertex names the plant vertex it comes from, so normals, uvs, colours and the Luft
// shading carry over; each triangle names the triangle whose ids and role it keeps.
// Deterministic; computed once per plant and cached (npr/foliage_cache.h's ResultCache).
#pragma once

#include <cstddef>
#include <vector>

#include "core/cache/result_cache.h"
#include "core/scene/lod.h"
#include "core/scene/scene.h"

namespace sylva {

inline constexpr size_t kLodLeafTriangles = 8;  // a smaller foliage component is pruned

// The levels of `plant` (a plant as a scene of its own, core/scene/instances.h: roles and
// primitive ids set).
PlantLod make_plant_lod(const Scene& plant);

// Every plant's levels (a flat scene: none), each read from or stored in `cache` (nullptr:
// computed) under a key of the plant's meshes and this code's version.
std::vector<PlantLod> scene_lods(const Scene& scene, const ResultCache* cache);

}  // namespace sylva
