// Ambient occlusion as a scene-level render-graph node (DESIGN.md §3): the ao.* parameters,
// and the node that fits Hegeman et al.'s shells (npr/ao_shells.h) to the foliage vertices
// once per scene and writes "ao-shading" (std::shared_ptr<const AoShading>, the uniforms the
// raster pass evaluates per fragment into its AO target and the colour's ambient term). The
// raster pass reads the node only when ao.model is not none, so compile() culls it otherwise.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/gl/rasterizer.h"
#include "core/graph/render_graph.h"
#include "core/params.h"
#include "core/scene/scene.h"
#include "npr/ao_reference.h"
#include "npr/hegeman_ao.h"

namespace sylva {

// ao.model. None: no AO (the AO target is 1 on geometry, images unchanged). Hegeman*: leaves
// by Hegeman et al. Eq. 4-6 in their shell; wood, ground and other geometry by the solid angle
// of the crown's bounding sphere (Eq. 7-8, core/gl/ao_shading.h); grass blades by Eq. 9 times
// that. Raytraced: the ao buffer only (a pass after the raster pass); the colour's ambient term
// is not darkened by it.
enum class AoModel {
  None,
  Constant,
  LuftDensity,
  HegemanSphere,
  HegemanEllipsoid,
  HegemanShells,
  Raytraced,
};
// The names of the models as ao.model takes them: none, constant, luft-density,
// hegeman-sphere, hegeman-ellipsoid, hegeman-shells, raytraced (in that order).
const std::vector<std::pair<std::string, AoModel>>& ao_model_choices();
// One of ao_model_choices' names; throws InputError(where, ...) naming them.
AoModel parse_ao_model(const std::string& name, const std::string& where);
const std::string& ao_model_name(AoModel model);

// The ao.* preset keys as a user gives them.
struct AoSettings {
  AoModel model = AoModel::None;
  // constant: the visibility everywhere, [0, 1]. 0.6 is about the mean ray-traced visibility
  // of the sample crowns' leaves, so switching from hegeman-* keeps the overall tone.
  float constant = 0.6f;
  // Hegeman et al. Eq. 6 alpha * rho: "auto" (fitted by least squares, npr/ao_fit.h, to
  // ray-traced visibility at 256 foliage vertices, 64 rays, seeded by the scene seed) or a
  // number >= 0 per scene unit cubed (npr/hegeman_ao.h).
  std::string alpha_rho = "auto";
  int shells = 4;  // hegeman-shells: k, [1, 64]
  // hegeman-*: the crown's solid angle that occludes non-foliage (Hegeman et al. Eq. 7-8):
  // exact (default) 2 pi (1 - sqrt(1 - (r/d)^2)) or paper pi (r/d)^2 (Eq. 7).
  SolidAngleModel solid_angle = SolidAngleModel::Exact;
  int rays = 64;  // raytraced: rays per pixel, [1, 4096]
};

// Binds ao.model, ao.constant, ao.alpha_rho, ao.shells, ao.solid_angle and ao.rays with
// their ranges.
void bind_ao_params(ParamSet& set, AoSettings& s);
// What the raster pass evaluates for the model (raytraced: None, the raster pass draws no
// AO). Throws InputError("ao.model", ...) for a value that is none of the models.
AoShading::Model ao_model_of(AoModel model);

// The ray tracer over every scene triangle; alpha-MASK/BLEND materials with a base-colour
// texture let rays through texels whose alpha (times the material's) is below the cutoff
// (BLEND: 0.5, as the raster pass draws it), nearest texel, repeat wrapping.
AoReferenceScene make_scene_tracer(const Scene& scene);

// What the frames of one scene (a turntable, a keyframe study) compute once and share: the
// fitted shells per ao.* settings and seed, and the ray tracer's BVH. Thread-safe.
struct AoMemo {
  std::mutex mutex;
  std::map<std::string, std::shared_ptr<const AoShading>> shading;  // by ao_memo_key
  std::shared_ptr<const AoReferenceScene> tracer;                   // make_scene_tracer
};

// The key of `settings` and `seed` in AoMemo::shading.
std::string ao_memo_key(const AoSettings& settings, uint64_t seed);

struct AoSetup {
  const Scene* scene = nullptr;  // outlives execute()
  AoSettings settings;
  uint64_t seed = 1;  // k-means seeding and the alpha_rho fit's samples and rays
  // Shared across graphs over the same scene: the node fits once and reuses the result.
  // Null: fit on every execute().
  std::shared_ptr<AoMemo> memo;
};

// What the AO node computes for `settings` (ao_model_of; for hegeman-*: the shells fitted to
// the foliage vertices, k = 1 for sphere and ellipsoid, seeded by `seed`, and alpha_rho as
// given or, for auto, fitted to ray-traced visibility (make_scene_tracer, 64 rays) at up to
// 256 foliage-triangle centroids picked with `seed`); the crown sphere occluding the rest
// (Eq. 7-8) is the foliage's bounding sphere, and grass (Role::Grass triangles, Eq. 9) has
// its roots at their lowest y and the height of their extent in y. Flat ground (Role::Ground
// triangles all at one y, within 1e-6 of their extent) is the ground plane that also darkens
// wood and other geometry (AoShading::ground_plane). A scene with grass but no foliage gets
// no shells and no crown (grass by Eq. 9 alone). A scene of many plants gets each plant's
// shells and every instance's crown (npr/ao_plants.h). Throws
// InputError("ao.model", ...) for hegeman-* on a scene with neither foliage nor grass.
AoShading scene_ao_shading(const Scene& scene, const AoSettings& settings, uint64_t seed);

// The foliage vertices (those of triangles with Role::Foliage), world space.
std::vector<glm::vec3> foliage_vertices(const Scene& scene);

// Returns the "ao-shading" resource. The node fits the shells (hegeman-*; k = 1 for sphere
// and ellipsoid) and alpha_rho when asked (or takes them from setup.memo); for constant /
// luft-density it only passes the model on. Throws InputError("ao.*", ...) when run on a scene
// without foliage for hegeman-*.
Handle<std::shared_ptr<const AoShading>> add_ao_shading_pass(RenderGraph& graph, AoSetup setup);

// ao.model = raytraced: reads the raster pass's view-space "position" and "normal" targets and
// writes "ao-raytraced" (CV_32FC1, AoReferenceScene::visibility with `rays` rays seeded by
// `seed` at each covered pixel, moved to world space by inverse(view); background 0). With
// `memo`, Embree's BVH over the scene is built once and shared.
Handle<cv::Mat> add_raytraced_ao_pass(RenderGraph& graph, const Scene* scene,
                                      Handle<cv::Mat> position, Handle<cv::Mat> normal,
                                      const glm::mat4& view, int rays, uint64_t seed,
                                      std::shared_ptr<AoMemo> memo = nullptr);

}  // namespace sylva
