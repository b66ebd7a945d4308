// The raster pass: one indexed draw per mesh (an instanced scene: per plant mesh, instanced
// over the plant's visible instances, core/gl/instance_draws.h) into a framebuffer with only
// the requested targets attached (MRT). Colour is Luft et al. Eq. 1 local illumination: ambient *
// ka + sum over lights of diffuse + specular, with ka decoded from the normal's length and the
// normal re-normalised in the vertex shader. Leaves are drawn double-sided (normal flipped
// with gl_FrontFacing); alpha-MASK materials discard fragments below the cutoff from the
// base-colour texture's alpha, so every target follows the leaf shape; BLEND materials are
// drawn the same way with cutoff 0.5 (a G-buffer holds one surface per pixel). SSAA renders
// at ssaa x size and down-samples per kind (see downsample.h: colour averaged in linear
// light, normal/depth/position/ka averaged over covered samples, ids by majority).
#pragma once

#include <memory>

#include "core/gl/ao_shading.h"
#include "core/gl/camera.h"
#include "core/gl/gbuffer.h"
#include "core/gl/gl_context.h"
#include "core/gl/lights.h"
#include "core/scene/lod.h"
#include "core/scene/scene.h"

namespace sylva {

struct RasterRequest {
  TargetMask targets = static_cast<TargetMask>(Target::Color);
  IdKind id_kind = IdKind::Primitive;
  int ssaa = 1;                      // supersampling factor per axis, [1, 4]
  glm::vec4 background{1, 1, 1, 0};  // colour target clear, linear RGBA
  bool scaled_normals = false;       // normal target keeps |N| = ka (Luft Fig. 7c), not unit
  bool flat_albedo = false;          // albedo target: each texture's mean colour (flat toon tones)
  AoShading ao;                      // the AO target and the colour's ambient visibility
  uint32_t only_cluster = 0;         // > 0: draw only the triangles of this cluster id
  bool id_samples = false;           // keep the id target's samples too (GBuffer::id_samples)
};

// Replacement per-vertex shading inputs, per scene mesh (scene order): normals (world
// space; their length may carry ka) and optional separate ka (empty = from |normal|).
// What the Luft preprocessing produces.
struct VertexShading {
  std::vector<std::vector<glm::vec3>> normals;
  std::vector<std::vector<float>> ka;
  // Foliage normals already face outward (realigned): double-sided leaves do not flip them
  // for back faces, or half the crown would be lit from inside.
  bool oriented_foliage = false;
};

// How the draws are split. llvmpipe shades every vertex a draw call references into one buffer
// (~100 bytes a vertex), and bins the triangles of many instanced draws ahead of its rasteriser
// threads (up to 64 scenes, each up to tens of MB) when they fall behind: on a CPU renderer a
// mesh is drawn in chunks, and the draws of a forest wait for the rasteriser (glFinish) every
// `queued_triangles`, so memory stays bounded whatever the mesh or the number of instances. A
// GPU driver bounds its own queues: one draw per mesh and batch, no waits. 0 = no limit. The
// pictures are the same either way (the same triangles in the same order).
struct DrawLimits {
  size_t chunk_triangles = 0;   // triangles per draw call (the CPU renderer's: 32768)
  size_t queued_triangles = 0;  // instanced triangles between waits (the CPU renderer's: 2^17)
};
DrawLimits draw_limits_for(const GlInfo& info);

class Rasterizer {
 public:
  // The context must outlive the Rasterizer; GL objects are created in it on upload/render.
  explicit Rasterizer(GlContext& context);
  ~Rasterizer();
  Rasterizer(const Rasterizer&) = delete;
  Rasterizer& operator=(const Rasterizer&) = delete;

  // Uploads geometry, ids and textures. Call again when the scene changes.
  void upload(const Scene& scene);
  // Levels of detail of an instanced scene's plants (npr/plant_lod.h; after upload(), one
  // PlantLod per plant): from then on each instance is drawn at the level its projected size
  // asks for (core/gl/instance_draws.h). Empty, or a flat scene: every instance whole.
  void set_lod(const Scene& scene, const std::vector<PlantLod>& lods);
  // Replaces the uploaded normals/ka of the meshes `shading` covers (and of their levels of
  // detail); the rest keep theirs.
  void set_vertex_shading(const VertexShading& shading);
  // The same, kept: a second call with the shading in place (the same object, nothing replaced
  // since) uploads nothing, so a turntable's frames share one upload.
  void set_vertex_shading(std::shared_ptr<const VertexShading> shading);
  // Puts the uploaded scene's own normals and ka back after set_vertex_shading (nothing to do
  // when they were not replaced).
  void restore_vertex_shading();
  GBuffer render(const Camera& camera, const Lighting& lighting, const RasterRequest& request);

  // Replaces the limits draw_limits_for(context.info()) chose (tests of the GPU's way on llvmpipe).
  void set_draw_limits(const DrawLimits& limits);

  // Targets allocated by the most recent render (for tests of the render graph's culling).
  TargetMask last_allocated_targets() const;
  // Instances the most recent render drew (those in view; a flat scene: 1).
  size_t last_drawn_instances() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sylva
