#include "core/gl/rasterizer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "core/gl/ao_buffers.h"
#include "core/gl/gpu_scene.h"
#include "core/gl/instance_draws.h"
#include "core/gl/lod_meshes.h"
#include "core/gl/raster_uniforms.h"
#include "core/gl/shaders.h"
#include "core/gl/target_slots.h"

namespace sylva {

namespace {

// Framebuffer memory allowed for one render (attachments only; read-back needs about as much
// again): 4 GiB fits 4096^2 at SSAA 2 with every target.
constexpr double kMaxFramebufferBytes = 4.0 * (1u << 30);

float srgb_encode(float c) {
  return linear_to_srgb(c);
}

}  // namespace

struct Rasterizer::Impl {
  GlContext& context;
  std::vector<GpuMesh> meshes;
  std::vector<std::vector<size_t>> plant_meshes;  // instanced: per plant, indices into meshes
  LodMeshes lod;                                  // levels of detail (set_lod)
  InstanceDraws instances;
  AoBuffers ao_buffers;  // a scene of many plants' AO (instanced programs only)
  size_t drawn_instances = 0;
  size_t queued_triangles = 0;  // instanced triangles drawn since the last glFinish
  std::vector<GLuint> textures;
  std::vector<glm::vec3> texture_means;  // linear mean colour of each texture's opaque texels
  std::vector<Material> materials;
  // The scene's own normals, ka and orientation per scene mesh, for restore_vertex_shading.
  std::vector<std::vector<glm::vec3>> own_normals;
  std::vector<std::vector<float>> own_ka;
  std::vector<char> own_outward;
  std::vector<std::string> mesh_names;
  bool shading_replaced = false;
  std::shared_ptr<const VertexShading> kept_shading;  // in place since set_vertex_shading
  std::map<uint32_t, RasterProgram> programs;         // by target mask | alpha test << 16
  GLuint fbo = 0;
  GLuint depth_texture = 0;
  std::array<GLuint, kSlots> slot_textures{};
  int fbo_width = 0, fbo_height = 0;
  TargetMask fbo_targets = 0;

  DrawLimits limits;

  explicit Impl(GlContext& c) : context(c), limits(draw_limits_for(c.info())) {}

  void release_scene() {
    for (GpuMesh& m : meshes) {
      release_mesh(m);
    }
    meshes.clear();
    plant_meshes.clear();
    lod.release();
    instances.release();
    ao_buffers.release();
    if (!textures.empty()) glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
    textures.clear();
    texture_means.clear();
    materials.clear();
    own_normals.clear();
    own_ka.clear();
    own_outward.clear();
    mesh_names.clear();
    shading_replaced = false;
    kept_shading.reset();
  }

  void release_fbo() {
    if (fbo) glDeleteFramebuffers(1, &fbo);
    if (depth_texture) glDeleteTextures(1, &depth_texture);
    for (GLuint& t : slot_textures) {
      if (t) glDeleteTextures(1, &t);
      t = 0;
    }
    fbo = depth_texture = 0;
    fbo_width = fbo_height = 0;
    fbo_targets = 0;
  }

  const RasterProgram& program(TargetMask targets, bool alpha_test) {
    const bool instanced = instances.instanced();
    const uint32_t key = targets | (alpha_test ? 1u << 16 : 0u) | (instanced ? 1u << 17 : 0u);
    auto it = programs.find(key);
    if (it == programs.end()) {
      it = programs.emplace(key, make_raster_program(targets, alpha_test, instanced)).first;
    }
    return it->second;
  }

  // Only the requested targets are attached; the FBO is rebuilt when size or targets change.
  void ensure_fbo(int width, int height, TargetMask targets) {
    if (fbo && width == fbo_width && height == fbo_height && targets == fbo_targets) return;
    release_fbo();
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    depth_texture = make_target_texture(GL_DEPTH_COMPONENT32F, width, height);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_texture, 0);
    std::array<GLenum, kSlots> draw_buffers{};
    for (int i = 0; i < kSlots; ++i) {
      draw_buffers[i] = GL_NONE;
      if (!has(targets, kAllTargets[i])) continue;
      slot_textures[i] = make_target_texture(slot_format(i).internal_format, width, height);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D,
                             slot_textures[i], 0);
      draw_buffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glDrawBuffers(kSlots, draw_buffers.data());
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      release_fbo();
      check_gl_errors("raster pass framebuffer");  // a GPU out of memory says so
      throw std::runtime_error("raster pass: framebuffer incomplete (status " +
                               std::to_string(status) + ")");
    }
    fbo_width = width;
    fbo_height = height;
    fbo_targets = targets;
  }

  void clear(const glm::vec4& background) {
    for (int i = 0; i < kSlots; ++i) {
      const Target t = kAllTargets[i];
      if (!has(fbo_targets, t)) continue;
      if (t == Target::Id) {
        const GLuint zero[4] = {0, 0, 0, 0};
        glClearBufferuiv(GL_COLOR, i, zero);
      } else if (t == Target::Color) {
        const GLfloat c[4] = {srgb_encode(background.r), srgb_encode(background.g),
                              srgb_encode(background.b), std::clamp(background.a, 0.0f, 1.0f)};
        glClearBufferfv(GL_COLOR, i, c);
      } else {
        const GLfloat zero[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, i, zero);
      }
    }
    const GLfloat far_depth = 1.0f;
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
  }

  // Material, program and per-mesh state for drawing `m`; returns the program in use.
  const RasterProgram& prepare_mesh(const GpuMesh& m, TargetMask targets, const Camera& camera,
                                    const Lighting& lighting, const RasterRequest& request,
                                    std::array<const RasterProgram*, 2>& variants) {
    static const Material fallback = default_material();
    const Material& mat = m.material >= 0 ? materials[m.material] : fallback;
    const bool has_texture = mat.base_color_texture >= 0;
    // BLEND is drawn as MASK with cutoff 0.5: G-buffers hold one surface per pixel.
    const bool alpha_test = mat.alpha_mode != AlphaMode::Opaque;
    const float cutoff = mat.alpha_mode == AlphaMode::Mask ? mat.alpha_cutoff : 0.5f;
    const RasterProgram*& variant = variants[alpha_test ? 1 : 0];
    if (!variant) {
      variant = &program(targets, alpha_test);
      set_frame_uniforms(*variant, camera, lighting, request, instances.branch_cluster());
      if (instances.instanced()) ao_buffers.bind(*variant);
    }
    const RasterProgram& p = *variant;
    glUseProgram(p.id);
    glUniform1ui(p.object_id, request.id_kind == IdKind::Material ? material_id(m) : m.object_id);
    glUniform4fv(p.base_color, 1, &mat.base_color[0]);
    glUniform1i(p.has_texture, has_texture ? 1 : 0);
    glUniform1f(p.alpha_cutoff, cutoff);
    glUniform1i(p.double_sided, mat.double_sided ? 1 : 0);
    glUniform1i(p.oriented_foliage, m.oriented_foliage ? 1 : 0);
    glUniform1i(p.has_normals, m.has_normals ? 1 : 0);
    if (has_texture) {
      glBindTexture(GL_TEXTURE_2D, textures[mat.base_color_texture]);
      glUniform3fv(p.texture_mean, 1, &texture_means[mat.base_color_texture][0]);
    }
    if (mat.double_sided) {
      glDisable(GL_CULL_FACE);
    } else {
      glEnable(GL_CULL_FACE);
    }
    // Absent optional attributes read these constants (context state, not VAO state).
    glVertexAttrib2f(kAttribUv, 0.0f, 0.0f);
    glVertexAttrib4f(kAttribColor, 1.0f, 1.0f, 1.0f, 1.0f);
    glVertexAttrib3f(kAttribNormal, 0.0f, 0.0f, 1.0f);
    glVertexAttrib1f(kAttribKa, -1.0f);
    glBindVertexArray(m.vao);
    return p;
  }

  // In pieces of at most `limits` (draw_limits_for): the chunks and waits a CPU renderer
  // needs to keep its memory bounded; with no limits, one draw per mesh and batch.
  void draw_chunks(const GpuMesh& m, GLsizei instance_count) {
    const auto chunk_indices = GLsizei(
        limits.chunk_triangles ? std::min<size_t>(3 * limits.chunk_triangles, size_t(1) << 30)
                               : size_t(std::max(m.index_count, 1)));
    const size_t queue_limit = limits.queued_triangles;
    for (GLsizei first = 0; first < m.index_count; first += chunk_indices) {
      const GLsizei count = std::min(chunk_indices, m.index_count - first);
      const void* offset = reinterpret_cast<const void*>(size_t(first) * sizeof(uint32_t));
      if (instance_count == 0) {
        glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, offset);
        continue;
      }
      const size_t triangles = size_t(count / 3);
      const auto per_draw =
          queue_limit ? GLsizei(std::max<size_t>(1, queue_limit / triangles)) : instance_count;
      for (GLsizei i = 0; i < instance_count; i += per_draw) {
        const GLsizei n = std::min(per_draw, instance_count - i);
        if (queue_limit && queued_triangles + triangles * size_t(n) > queue_limit) {
          glFinish();
          queued_triangles = 0;
        }
        glDrawElementsInstancedBaseInstance(GL_TRIANGLES, count, GL_UNSIGNED_INT, offset, n,
                                            GLuint(i));
        queued_triangles += triangles * size_t(n);
      }
    }
  }

  void draw_meshes(TargetMask targets, const Camera& camera, const Lighting& lighting,
                   const RasterRequest& request) {
    std::array<const RasterProgram*, 2> variants{};  // by alpha test
    if (!instances.instanced()) {
      for (const GpuMesh& m : meshes) {
        prepare_mesh(m, targets, camera, lighting, request, variants);
        draw_chunks(m, 0);
      }
      drawn_instances = 1;
    } else {
      // Mirrored instances (a negative determinant) turn their triangles' winding around.
      for (const InstanceBatch& batch : instances.prepare(camera, request.ssaa, &drawn_instances)) {
        glFrontFace(batch.mirrored ? GL_CW : GL_CCW);
        const bool whole = batch.level == 0;
        const std::vector<GpuMesh>& pool = whole ? meshes : lod.meshes();
        for (size_t mi : whole ? plant_meshes[batch.plant] : lod.of(batch.plant, batch.level)) {
          prepare_mesh(pool[mi], targets, camera, lighting, request, variants);
          instances.bind(batch);
          draw_chunks(pool[mi], batch.count);
        }
      }
      glFrontFace(GL_CCW);
    }
    glBindVertexArray(0);
  }

  uint32_t material_id(const GpuMesh& m) const {
    return m.material >= 0 ? uint32_t(m.material) + 1 : uint32_t(materials.size()) + 1;
  }
};

Rasterizer::Rasterizer(GlContext& context) : m_impl(std::make_unique<Impl>(context)) {}

Rasterizer::~Rasterizer() {
  m_impl->context.make_current();
  m_impl->release_scene();
  m_impl->release_fbo();
  for (auto& [mask, p] : m_impl->programs)
    glDeleteProgram(p.id);
}

void Rasterizer::upload(const Scene& scene) {
  Impl& s = *m_impl;
  s.context.make_current();
  s.release_scene();
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const int tex = scene.materials[i].base_color_texture;
    if (tex >= static_cast<int>(scene.textures.size())) {
      throw InputError("material '" + scene.materials[i].name + "'", "texture index out of range");
    }
  }
  s.materials = scene.materials;
  for (const Texture& t : scene.textures) {
    s.textures.push_back(upload_texture(t));
    s.texture_means.push_back(texture_mean(t));
  }
  for (const Mesh& mesh : scene.meshes) {  // by scene mesh index, to restore them
    s.own_normals.push_back(mesh.normals);
    s.own_ka.push_back(mesh.ka);
    s.own_outward.push_back(mesh.outward_normals ? 1 : 0);
    s.mesh_names.push_back(mesh.name);
  }
  s.instances.upload(scene);
  s.plant_meshes.assign(scene.instanced() ? scene.plants.size() : 0, {});
  for (size_t p = 0; p < scene.plant_count(); ++p) {
    const std::vector<uint32_t> meshes = plant_meshes(scene, p);
    for (size_t k = 0; k < meshes.size(); ++k) {
      const Mesh& mesh = scene.meshes[meshes[k]];
      if (mesh.material >= static_cast<int>(scene.materials.size())) {
        throw InputError("mesh '" + mesh.name + "'", "material index out of range");
      }
      if (mesh.triangle_count() == 0 || mesh.positions.empty()) continue;
      // Object ids: the mesh's index in its plant + 1 (a flat scene: in the scene).
      s.meshes.push_back(upload_mesh(mesh, static_cast<uint32_t>(k + 1)));
      s.meshes.back().scene_index = meshes[k];
      if (scene.instanced()) s.plant_meshes[p].push_back(s.meshes.size() - 1);
    }
  }
  check_gl_errors("scene upload");
}

void Rasterizer::set_lod(const Scene& scene, const std::vector<PlantLod>& lods) {
  Impl& s = *m_impl;
  s.context.make_current();
  s.lod.release();
  s.kept_shading.reset();  // the new levels have the scene's own normals
  if (!scene.instanced() || lods.empty()) return;
  s.lod.upload(scene, lods);
  std::vector<size_t> triangles;
  std::vector<int> levels;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    size_t n = 0;
    for (uint32_t mi : scene.plants[p].meshes)
      n += scene.meshes[mi].triangle_count();
    triangles.push_back(n);
    levels.push_back(int(lods[p].levels.size()));
  }
  s.instances.set_levels(triangles, levels);
}

void Rasterizer::set_vertex_shading(std::shared_ptr<const VertexShading> shading) {
  SYLVA_CHECK(shading != nullptr, "set_vertex_shading without shading");
  if (shading == m_impl->kept_shading) return;
  set_vertex_shading(*shading);
  m_impl->kept_shading = std::move(shading);
}

void Rasterizer::set_vertex_shading(const VertexShading& shading) {
  Impl& s = *m_impl;
  s.context.make_current();
  s.kept_shading.reset();
  s.lod.set_shading(shading);
  for (GpuMesh& m : s.meshes) {
    const size_t i = m.scene_index;
    if (i >= shading.normals.size()) continue;
    static const std::vector<float> kNone;
    replace_shading(m, shading.normals[i], i < shading.ka.size() ? shading.ka[i] : kNone,
                    "mesh " + std::to_string(i));
    m.oriented_foliage = shading.oriented_foliage;
  }
  s.shading_replaced = true;
}

void Rasterizer::restore_vertex_shading() {
  Impl& s = *m_impl;
  if (!s.shading_replaced) return;
  s.kept_shading.reset();
  s.context.make_current();
  for (GpuMesh& m : s.meshes) {
    const size_t i = m.scene_index;
    replace_shading(m, s.own_normals[i], s.own_ka[i], s.mesh_names[i]);
    m.oriented_foliage = s.own_outward[i] != 0;
  }
  // The levels of detail take one orientation for every mesh: outward when all are (a baked
  // file's).
  const bool all_outward = std::all_of(s.own_outward.begin(), s.own_outward.end(),
                                       [](char outward) { return outward != 0; });
  s.lod.set_shading(VertexShading{s.own_normals, s.own_ka, all_outward && !s.own_outward.empty()});
  s.shading_replaced = false;
}

GBuffer Rasterizer::render(const Camera& camera, const Lighting& lighting,
                           const RasterRequest& request) {
  Impl& s = *m_impl;
  SYLVA_CHECK(request.targets != 0 && (request.targets & ~kAllTargetsMask) == 0,
              "raster request needs at least one known target");
  SYLVA_CHECK(camera.width >= 1 && camera.height >= 1, "camera without a size");
  validate_request(request);
  validate_lighting(lighting);
  s.context.make_current();

  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  const int width = camera.width * request.ssaa;
  const int height = camera.height * request.ssaa;
  if (width > max_size || height > max_size) {
    throw InputError("--ssaa", "size x ssaa exceeds the GL limit of " + std::to_string(max_size) +
                                   " pixels per side");
  }
  const double bytes = framebuffer_bytes(request.targets, width, height);
  if (bytes > kMaxFramebufferBytes) {
    throw InputError("--ssaa", "size x ssaa with these targets needs " +
                                   std::to_string(static_cast<long>(bytes / (1 << 20))) +
                                   " MiB of framebuffer (limit 4096 MiB); lower --size or --ssaa");
  }
  s.ensure_fbo(width, height, request.targets);

  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.fbo);
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glActiveTexture(GL_TEXTURE0);
  if (s.instances.instanced()) s.ao_buffers.upload(request.ao);
  s.clear(request.background);  // the FBO is bound as the draw framebuffer
  s.draw_meshes(request.targets, camera, lighting, request);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  GBuffer out =
      read_targets(s.fbo, width, height, request.targets, request.ssaa, request.id_samples);
  check_gl_errors("raster pass at " + std::to_string(width) + "x" + std::to_string(height));
  return out;
}

DrawLimits draw_limits_for(const GlInfo& info) {
  if (!info.software) return {};
  return {32768, size_t(1) << 17};
}

void Rasterizer::set_draw_limits(const DrawLimits& limits) {
  m_impl->limits = limits;
}

TargetMask Rasterizer::last_allocated_targets() const {
  return m_impl->fbo_targets;
}

size_t Rasterizer::last_drawn_instances() const {
  return m_impl->drawn_instances;
}

}  // namespace sylva
