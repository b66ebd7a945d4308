// Expressive foliage illumination (Luft, Balzer & Deussen 2007), the whole preprocessing:
// generators from the leaves (§3.1) → density field (Eq. 2, 3) sampled on a grid → implicit
// surface (marching cubes) → realigned foliage normals (§3.3) → ambient coefficient ka per
// vertex from the density by Eq. 4 (§3.2), for foliage and wood alike.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/gl/rasterizer.h"
#include "core/scene/scene.h"
#include "core/scene/scene_length.h"
#include "npr/ambient.h"
#include "npr/implicit_surface.h"

namespace sylva {

// Where a foliage vertex's new normal comes from.
enum class NormalSource {
  Surface,   // the nearest implicit-surface vertex's normal (Luft §3.3)
  Gradient,  // -grad F at the vertex itself, no surface needed
};

// How ka reaches the renderer: in the normal's length (Luft §3.2) or as its own attribute.
enum class KaEncoding { Length, Attribute };

struct FoliageParams {
  // Radius of influence rho; auto = max(8% of the foliage diagonal, 3 x the mean leaf
  // spacing), relative values are % of the foliage bounding-box diagonal.
  SceneLength rho;
  // When > 0 (scene units), rho = auto becomes max(picture_rho, 3 x the mean leaf spacing):
  // the radius set by a style's picture scale (ink.detail, passes/ink_lines.h), so the
  // realigned normals are smooth at the scale the picture draws.
  double picture_rho = 0.0;
  // Threshold tau >= 0 (density units); nullopt = auto: half the 10th percentile of the
  // summed kernels at the generators, so the surface wraps nearly every leaf.
  std::optional<float> tau;
  // Share of leaves used as generators, (0, 1]; nullopt = auto: all of them up to a splat
  // budget of 2^28 kernel evaluations at this grid, fewer beyond (Luft §3.1's speed-up).
  std::optional<double> fraction;
  bool per_triangle = false;  // one generator per foliage triangle instead of per leaf
  int grid = 128;             // marching-cubes cells along the longest axis, [2, 1024]
  float blend = 1.0f;         // N' = normalize((1 - blend) N + blend N_s), [0, 1]
  NormalSource normals = NormalSource::Surface;
  // Eq. 4. ambient.d_min is ignored when d_min_auto (then: the 90th percentile of F over
  // the foliage vertices, so the densest tenth of the crown is at ka_min).
  AmbientParams ambient;
  bool d_min_auto = true;
  SurfaceOptimizeOptions optimize;  // tech report: smoothing / decimation of the surface
  uint64_t seed = 1;                // which leaves the fraction keeps
};

// Throws InputError naming the parameter and its range.
void validate_foliage_params(const FoliageParams& params);

struct FoliageStats {
  size_t leaves = 0, generators = 0;
  double rho = 0, tau = 0, fraction = 1, d_min = 0;
  double density_min = 0, density_max = 0;  // F over all shaded vertices
  size_t surface_triangles = 0;
  double seconds_field = 0, seconds_surface = 0, seconds_shading = 0;
  bool from_cache = false;  // read from the result cache (timings are the computing run's)
  // An instanced scene: each plant's own (leaves, generators, surface triangles and timings
  // above are their sums; rho, tau, d_min and F those of the first plant with foliage).
  std::string plant;  // the plant's name (in `plants`)
  std::vector<FoliageStats> plants;
};

struct FoliageIllumination {
  // Per scene mesh, per vertex: unit normals (realigned on foliage, the mesh's own
  // elsewhere; computed when a mesh has none) and ka in [ka_min, 1].
  std::vector<std::vector<glm::vec3>> normals;
  std::vector<std::vector<float>> ka;
  SurfaceMesh surface;  // empty with NormalSource::Gradient, and for an instanced scene
  // An instanced scene: each plant's surface in plant space (empty for a plant without
  // foliage and with NormalSource::Gradient).
  std::vector<SurfaceMesh> plant_surfaces;
  FoliageStats stats;
};

// Needs roles and primitive ids (finish_scene). Throws InputError when the scene has no
// foliage, or when tau leaves no surface ("tau 12 is above every density; F + tau spans
// [0, 9.5] with rho 0.4"). Deterministic. An instanced scene runs once per plant in plant
// space (relative parameters relative to that plant); a plant without foliage keeps its
// own unit normals with ka 1 (no density reaches it).
FoliageIllumination compute_foliage_illumination(const Scene& scene, const FoliageParams& params);

// For an instanced scene, `one` run on each plant with foliage as a scene of its own
// (plant_scene, plant space) and the results merged per scene mesh; a plant without
// foliage keeps its own unit normals with ka 1. A flat scene: one(scene). Throws
// InputError("scene", ...) when no plant has foliage.
FoliageIllumination foliage_per_plant(const Scene& scene,
                                      const std::function<FoliageIllumination(const Scene&)>& one);

// The renderer's input for an encoding: Length puts ka in |N| (floored at kKaFloor);
// Attribute keeps unit normals and passes ka separately.
VertexShading vertex_shading(const FoliageIllumination& result, KaEncoding encoding);

// A one-line summary for `sylva info`-style reports and progress output.
std::string describe(const FoliageStats& stats);

}  // namespace sylva
