#include "core/gl/raster_uniforms.h"

#include <array>
#include <cmath>

#include "core/error.h"

namespace sylva {

void set_frame_uniforms(const RasterProgram& p, const Camera& camera, const Lighting& lighting,
                        const RasterRequest& request, uint32_t branch_cluster) {
  const IdKind id_kind = request.id_kind;
  glUseProgram(p.id);
  glUniform1i(p.scaled_normals, request.scaled_normals ? 1 : 0);
  glUniform1i(p.flat_albedo, request.flat_albedo ? 1 : 0);
  glUniformMatrix4fv(p.view, 1, GL_FALSE, &camera.view[0][0]);
  glUniformMatrix4fv(p.proj, 1, GL_FALSE, &camera.proj[0][0]);
  glUniform1i(p.id_kind, id_kind == IdKind::Primitive ? 0
                         : id_kind == IdKind::Cluster ? 1
                         : id_kind == IdKind::Object  ? 2
                                                      : 3);
  glUniform1ui(p.only_cluster, request.only_cluster);
  glUniform1ui(p.branch_cluster, branch_cluster);
  glUniform1i(p.ortho, camera.ortho ? 1 : 0);
  glUniform1i(p.texture, 0);
  glUniform1f(p.ambient, lighting.ambient);
  // Scene-fixed lights are moved into view space here; camera-fixed ones already are.
  std::array<glm::vec4, kMaxLights> vectors{};
  std::array<glm::vec3, kMaxLights> colors{};
  std::array<glm::vec2, kMaxLights> specs{};
  const auto count = static_cast<int>(lighting.lights.size());
  for (int i = 0; i < count; ++i) {
    const Light& l = lighting.lights[i];
    if (l.type == Light::Type::Directional) {
      glm::vec3 d = l.camera_fixed ? l.vector : glm::mat3(camera.view) * l.vector;
      vectors[i] = glm::vec4(glm::normalize(d), 0.0f);
    } else {
      glm::vec3 p3 = l.camera_fixed ? l.vector : glm::vec3(camera.view * glm::vec4(l.vector, 1));
      vectors[i] = glm::vec4(p3, 1.0f);
    }
    colors[i] = l.color;
    specs[i] = glm::vec2(l.specular, l.shininess);
  }
  glUniform1i(p.light_count, count);
  glUniform4fv(p.light_vector, kMaxLights, &vectors[0][0]);
  glUniform3fv(p.light_color, kMaxLights, &colors[0][0]);
  glUniform2fv(p.light_spec, kMaxLights, &specs[0][0]);
  set_ao_uniforms(p, request.ao);
}

void set_ao_uniforms(const RasterProgram& p, const AoShading& ao) {
  glUniform1i(p.ao_model, static_cast<int>(ao.model));
  glUniform1f(p.ao_constant, ao.constant);
  glUniform1f(p.ao_alpha_rho, ao.alpha_rho);
  const int n = ao.model == AoShading::Model::Shells ? static_cast<int>(ao.centres.size()) : 0;
  glUniform1i(p.ao_shell_count, n);
  const bool crown = ao.model == AoShading::Model::Shells && ao.crown_radius > 0.0f;
  glUniform4f(p.ao_crown, ao.crown_centre.x, ao.crown_centre.y, ao.crown_centre.z,
              crown ? ao.crown_radius : 0.0f);
  glUniform1i(p.ao_exact_solid_angle, ao.exact_solid_angle ? 1 : 0);
  glUniform2f(p.ao_grass, ao.grass_ground, ao.grass_height);
  glUniform2f(p.ao_ground, ao.ground_y, ao.ground_plane ? 1.0f : 0.0f);
  if (n == 0) return;
  glUniform3fv(p.ao_centre, n, &ao.centres[0][0]);
  glUniform3fv(p.ao_anchor, n, &ao.anchors[0][0]);
  glUniformMatrix3fv(p.ao_inverse, n, GL_FALSE, &ao.inverse[0][0][0]);
  glUniformMatrix3fv(p.ao_transpose, n, GL_FALSE, &ao.transpose[0][0][0]);
  glUniform1fv(p.ao_volume_scale, n, ao.volume_scale.data());
}

void validate_request(const RasterRequest& request) {
  if (request.ssaa < 1 || request.ssaa > 4) throw InputError("--ssaa", "must be in [1, 4]");
  const AoShading& ao = request.ao;
  if (ao.model == AoShading::Model::Shells) {
    const size_t n = ao.centres.size();
    SYLVA_CHECK(n <= size_t(kMaxAoShells) && ao.anchors.size() == n && ao.inverse.size() == n &&
                    ao.transpose.size() == n && ao.volume_scale.size() == n,
                "AO shells: 0 to 64 shells, each with centre, anchor, matrices and volume");
    SYLVA_CHECK(std::isfinite(ao.crown_centre.x) && std::isfinite(ao.crown_centre.y) &&
                    std::isfinite(ao.crown_centre.z) && std::isfinite(ao.crown_radius) &&
                    std::isfinite(ao.grass_ground) && std::isfinite(ao.grass_height) &&
                    std::isfinite(ao.ground_y),
                "AO crown, grass and ground uniforms must be finite");
  }
  if (!(ao.constant >= 0.0f && ao.constant <= 1.0f))
    throw InputError("ao.constant", "must be in [0, 1]");
  if (!(std::isfinite(ao.alpha_rho) && ao.alpha_rho >= 0.0f))
    throw InputError("ao.alpha_rho", "must be finite and >= 0");
}

}  // namespace sylva
