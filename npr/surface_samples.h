// Points spread evenly over the surfaces of a scene's plants, for what is better computed from
// the scene than from pixels: the ink lines' crown coverage (passes/crown_coverage.h) is these
// points projected, so it moves with the scene from one view to the next and has none of the
// aliasing of leaves and needles thinner than a pixel.
//
// Every triangle but the ground (Role::Ground) is cut into k x k similar sub-triangles, k =
// ceil(sqrt(area) / spacing) clamped to [1, 16], and gets one point at each sub-triangle's
// centroid carrying the sub-triangle's area; on an alpha-cutout material a point where the
// texture cuts the leaf away (core/scene/texture_alpha.h) is left out. No randomness: the same
// scene and spacing give the same points.
//
// An instanced scene (core/scene/instances.h) is sampled once per plant, in the plant's own
// space at the spacing its largest instance needs, and the points are placed by every instance
// (positions and normals moved, areas scaled, clusters those of the id buffer). Past 2^22
// points (170 MB) each instance's points are thinned evenly by a seeded hash, their areas
// raised to keep the total: the coverage of a park stays right at the park's scale, while a
// close view of one of hundreds of trees gets fewer points than the tree alone would.
//
// A scene-level render-graph node (DESIGN.md §3) makes them once per scene: "surface-samples",
// a std::shared_ptr<const SurfaceSamples>, culled when no pass reads it.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <vector>

#include "core/graph/render_graph.h"
#include "core/scene/scene.h"

namespace sylva {

struct SurfaceSamples {
  std::vector<glm::vec3> positions;  // world space
  std::vector<glm::vec3> normals;    // unit: the triangle's geometric normal (either side)
  std::vector<float> areas;          // scene units², > 0
  std::vector<uint32_t> clusters;    // the triangle's cluster id (Mesh::cluster_ids; 0 = none)
  // The triangle's primitive id (Mesh::primitive_ids: a leaf; 0 = none), unique per plant.
  std::vector<uint32_t> primitives;
  std::vector<uint32_t> instances;  // a scene of many plants: the instance's index + 1; else empty
  float spacing = 0.0f;             // scene units
  size_t size() const { return positions.size(); }
};

// spacing: scene units, > 0 and finite (a programming error otherwise).
SurfaceSamples sample_surfaces(const Scene& scene, float spacing);

// The spacing the crown coverage uses: 1/400 of the diagonal of the bounds of every triangle but
// the ground (about 1 px when the plant fills a 512 px frame; world space, over every instance),
// so the points do not depend on the image size; 0 for a scene with no such triangle.
float coverage_spacing(const Scene& scene);

// Shared by the graphs of one scene (a turntable's frames): the samples are made once.
struct SurfaceSampleMemo {
  std::mutex mutex;
  std::shared_ptr<const SurfaceSamples> samples;
};

// The samples of `scene` at coverage_spacing, made once per memo (null: made now).
std::shared_ptr<const SurfaceSamples> coverage_samples(const Scene& scene, SurfaceSampleMemo* memo);

// Adds the node "surface-samples" over `scene` (outlives execute()) at coverage_spacing and
// returns its output. memo may be null (the samples are made on every execute()).
using SamplesHandle = Handle<std::shared_ptr<const SurfaceSamples>>;
SamplesHandle add_surface_samples_pass(RenderGraph& graph, const Scene* scene,
                                       std::shared_ptr<SurfaceSampleMemo> memo = nullptr);

}  // namespace sylva
