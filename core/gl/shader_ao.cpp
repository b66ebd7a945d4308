// The raster pass's ambient visibility in GLSL (Hegeman et al. Eq. 4-9, the models of
// core/gl/ao_shading.h), spliced into the fragment shader by shaders.cpp between its inputs
// and its main(); the same sums as npr/hegeman_ao.cpp's CPU versions.
#include "core/gl/shaders.h"

namespace sylva {

namespace {

const char* const kAoGlsl = R"GLSL(
// Hegeman et al. Eq. 4-6 for the point x with normal n in one shell (ball_cap in its unit
// ball), as npr/hegeman_ao.cpp's hegeman_visibility.
float shell_visibility(vec3 x, vec3 n, vec3 centre, mat3 inverse, mat3 transpose,
                       float volume_scale, float alpha_rho) {
  if (!(alpha_rho > 0.0) || !(volume_scale > 0.0)) return 1.0;
  vec3 to_centre = -(inverse * (x - centre));
  vec3 nu = transpose * n;
  float len = length(nu);
  float t = 0.0;
  vec3 in_plane = vec3(0.0);
  if (len > 0.0) {
    vec3 dir = nu / len;
    t = dot(dir, to_centre);
    in_plane = to_centre - t * dir;
  } else {
    t = -length(to_centre);  // zero normal: face away from the centre
  }
  float h = clamp(1.0 + t, 0.0, 2.0);
  float d = length(in_plane);
  float volume = 3.14159265358979 * h * h * (3.0 - h) / 3.0 * volume_scale;  // Eq. 4
  float h2 = h * h, d2 = d * d;
  float f = h2 + d2 > 0.0 ? clamp(h2 / (h2 + d2), 0.0, 1.0) : 1.0;  // Eq. 5
  float exponent = alpha_rho * f * volume;
  if (!(exponent > 0.0)) return 1.0;
  return clamp(exp(-exponent), 0.0, 1.0);  // Eq. 6
}

// The shell of the world point x is the one whose anchor is nearest (lowest index on ties).
float hegeman_visibility(vec3 x, vec3 n) {
  if (u_ao_shell_count <= 0) return 1.0;
  int s = 0;
  float best = 3.4e38;
  for (int i = 0; i < u_ao_shell_count; ++i) {
    vec3 e = x - u_ao_anchor[i];
    float d = dot(e, e);
    if (d < best) {
      best = d;
      s = i;
    }
  }
  return shell_visibility(x, n, u_ao_centre[s], u_ao_inverse[s], u_ao_transpose[s],
                          u_ao_volume_scale[s], u_ao_alpha_rho);
}

const float kPi = 3.14159265358979;

// The solid angle of a sphere with sin(half-angle) s, as npr/hegeman_ao.cpp's
// sphere_solid_angle: Eq. 7 or the exact 2 pi (1 - cos beta) without cancellation.
float sphere_solid_angle(float s, bool exact) {
  return exact ? 2.0 * kPi * s * s / (1.0 + sqrt(max(0.0, 1.0 - s * s))) : kPi * s * s;
}

// cone_solid_angle_above_horizon of npr/hegeman_ao.cpp (Mazonka 2012).
float cone_solid_angle_above_horizon(float beta, float gamma) {
  beta = clamp(beta, 0.0, kPi / 2.0);
  gamma = clamp(gamma, 0.0, kPi);
  float sb = sin(beta), cb = cos(beta);
  float full = 2.0 * kPi * sb * sb / (1.0 + cb);
  if (gamma + beta <= kPi / 2.0) return full;
  if (gamma - beta >= kPi / 2.0) return 0.0;
  float sg = sin(gamma), cg = cos(gamma);
  if (!(sg * sb > 0.0)) return cg > 0.0 ? full : 0.0;
  float a1 = acos(clamp(cg / sb, -1.0, 1.0));
  float a2 = acos(clamp(-cg * cb / (sg * sb), -1.0, 1.0));
  return clamp(2.0 * (kPi - a1 - cb * a2), 0.0, full);
}

// The solid angle of the crown sphere (centre, radius; radius <= 0: none) above x's tangent
// plane, as npr/hegeman_ao.cpp's object_visibility: clamped to its boundary value inside.
float crown_solid_angle(vec3 x, vec3 n, vec4 crown) {
  float r = crown.w;
  if (!(r > 0.0)) return 0.0;
  vec3 to_centre = crown.xyz - x;
  float dist = length(to_centre);
  float s = dist > r ? r / dist : 1.0;
  float a = sphere_solid_angle(s, u_ao_exact_solid_angle != 0);
  float n_len = length(n);
  if (n_len > 0.0) {
    float share = 0.5;  // x at the centre: no direction to the crown
    if (dist > 0.0) {
      float beta = dist > r ? asin(clamp(r / dist, 0.0, 1.0)) : kPi / 2.0;
      float gamma = acos(clamp(dot(n / n_len, to_centre / dist), -1.0, 1.0));
      float whole = sphere_solid_angle(sin(beta), true);
      share = whole > 0.0 ? cone_solid_angle_above_horizon(beta, gamma) / whole : 0.0;
    }
    a *= clamp(share, 0.0, 1.0);
  }
  return a;
}

// Hegeman et al. Eq. 7-8 with horizon clipping: the crown's sphere seen from x.
float object_visibility(vec3 x, vec3 n) {
  return clamp(1.0 - crown_solid_angle(x, n, u_ao_crown) / (2.0 * kPi), 0.0, 1.0);  // Eq. 8
}

#ifdef INSTANCED
// A scene of many plants (core/gl/ao_buffers.h): foliage by its own plant's shells in plant
// space; everything else by the solid angles of the crowns near it, summed.
float plant_hegeman_visibility(vec3 x, vec3 n) {
  uvec4 plant = ao_plants[v_plant];
  int first = int(plant.x), count = int(plant.y);
  if (count <= 0) return 1.0;
  int s = first;
  float best = 3.4e38;
  for (int i = first; i < first + count; ++i) {
    vec3 e = x - ao_shells[i].anchor.xyz;
    float d = dot(e, e);
    if (d < best) {
      best = d;
      s = i;
    }
  }
  AoShell shell = ao_shells[s];
  mat3 inverse = mat3(shell.inverse[0].xyz, shell.inverse[1].xyz, shell.inverse[2].xyz);
  mat3 transpose_ = mat3(shell.transpose[0].xyz, shell.transpose[1].xyz, shell.transpose[2].xyz);
  return shell_visibility(x, n, shell.centre.xyz, inverse, transpose_, shell.centre.w,
                          uintBitsToFloat(plant.z));
}

float crowns_visibility(vec3 x, vec3 n) {
  if (!(u_ao_grid.z > 0.0)) return 1.0;
  ivec2 cell = ivec2(floor((x.xz - u_ao_grid.xy) / u_ao_grid.z));
  if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, u_ao_grid_cells))) return 1.0;
  int at = 2 * (cell.y * u_ao_grid_cells.x + cell.x);
  uint offset = ao_grid[at], count = ao_grid[at + 1];
  float a = 0.0;
  for (uint i = 0u; i < count; ++i) {
    vec4 crown = ao_crowns[ao_grid[offset + i]];
    vec3 e = crown.xyz - x;
    float reach = 8.0 * crown.w;  // kAoCrownReach
    if (dot(e, e) <= reach * reach) a += crown_solid_angle(x, n, crown);
  }
  return clamp(1.0 - a / (2.0 * kPi), 0.0, 1.0);  // Eq. 8, the crowns' angles added
}
#endif

// Hegeman et al. Eq. 9, as npr/hegeman_ao.cpp's grass_visibility with up = +Y.
float grass_visibility(vec3 x, vec3 n) {
  float h = u_ao_grass.y;
  if (!(h > 0.0)) return 1.0;
  float pz = clamp(x.y - u_ao_grass.x, 0.0, h);
  float n_len = length(n);
  float cos_theta = n_len > 0.0 ? clamp(n.y / n_len, -1.0, 1.0) : 0.0;
  return clamp(pz / (2.0 * h) * (1.0 + cos_theta), 0.0, 1.0);
}

// The share of the hemisphere a flat ground below x hides, as npr/hegeman_ao.cpp's
// ground_plane_occlusion with up = +Y: theta / pi.
float ground_plane_occlusion(vec3 x, vec3 n) {
  if (u_ao_ground.y == 0.0 || !(x.y >= u_ao_ground.x)) return 0.0;
  float n_len = length(n);
  if (!(n_len > 0.0)) return 0.5;
  return clamp(acos(clamp(n.y / n_len, -1.0, 1.0)) / kPi, 0.0, 1.0);
}

// Hegeman models: the crown's own leaves by their shell (Eq. 4-6); everything else by the
// crown's solid angle (Eq. 7-8), grass blades also by their height (Eq. 9), wood and other
// geometry also by a flat ground under them.
float hegeman_model_visibility(vec3 x, vec3 n) {
#ifdef INSTANCED
  if (v_role == 0u)  // Role::Foliage, in its plant's space (normals back by M^T)
    return plant_hegeman_visibility(v_plant_pos, transpose(mat3(v_m0, v_m1, v_m2)) * n);
  float v = crowns_visibility(x, n);
#else
  if (v_role == 0u) return hegeman_visibility(x, n);  // Role::Foliage
  float v = object_visibility(x, n);
#endif
  if (v_role == 4u) v *= grass_visibility(x, n);  // Role::Grass
  if (v_role == 1u || v_role == 3u) v -= ground_plane_occlusion(x, n);  // Wood, Other
  return clamp(v, 0.0, 1.0);
}

float ambient_visibility(vec3 n_view) {
  if (u_ao_model == 1) return u_ao_constant;
  if (u_ao_model == 2) return clamp(v_ka, 0.0, 1.0);
  if (u_ao_model == 3)
    return hegeman_model_visibility(v_world_pos, transpose(mat3(u_view)) * n_view);
  return 1.0;
}

)GLSL";

}  // namespace

std::string raster_ao_glsl() {
  return kAoGlsl;
}

}  // namespace sylva
