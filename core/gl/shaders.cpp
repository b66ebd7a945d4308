#include "core/gl/shaders.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace sylva {

namespace {

const char* const kVertexBody = R"GLSL(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in vec4 a_color;
layout(location = 4) in uvec2 a_ids;
layout(location = 5) in uint a_role;
layout(location = 6) in float a_ka;  // a separate ambient coefficient, or -1: use |a_normal|
#ifdef INSTANCED
// Per instance (core/gl/instance_draws.h): plant space -> world, its normal matrix, and the
// bases added to the plant's own primitive, foliage cluster and object ids.
layout(location = 7) in mat4 a_model;
layout(location = 11) in mat3 a_normal_matrix;
layout(location = 14) in uvec4 a_id_base;  // w: the plant
uniform uint u_branch_cluster;  // the one cluster id of every instance's non-foliage
#endif

uniform mat4 u_view;
uniform mat4 u_proj;
uniform int u_id_kind;      // 0 primitive, 1 cluster, 2 object, 3 material
uniform uint u_object_id;   // mesh index + 1 (instanced: index in its plant + 1), or material id
uniform uint u_only_cluster;  // 0 = draw everything, else only this cluster's triangles

out vec3 v_view_pos;
out vec3 v_world_pos;
out vec3 v_normal;
out float v_ka;
out vec2 v_uv;
out vec4 v_color;
flat out uint v_id;
flat out uint v_role;
#ifdef INSTANCED
flat out uint v_plant;
out vec3 v_plant_pos;
flat out vec3 v_m0, v_m1, v_m2;
#endif

void main() {
  // Luft et al. Sec. 3.2: ka is stored as the normal's length; unit normals mean ka = 1.
  // A separate ka attribute, when the mesh has one, takes precedence.
  float len = length(a_normal);
  v_ka = clamp(a_ka >= 0.0 ? a_ka : len, 0.0, 1.0);
#ifdef INSTANCED
  vec3 world_pos = (a_model * vec4(a_position, 1.0)).xyz;
  vec3 world_normal = a_normal_matrix * a_normal;
  float world_len = length(world_normal);
  vec3 unit_normal = len > 1e-20 && world_len > 1e-20 ? world_normal / world_len : vec3(0.0);
  uvec2 ids = uvec2(a_ids.x + a_id_base.x, a_role == 0u || u_branch_cluster == 0u
                                               ? a_ids.y + a_id_base.y : u_branch_cluster);
  uint object_id = u_object_id + a_id_base.z;
  v_plant = a_id_base.w;
  v_plant_pos = a_position;
  v_m0 = a_model[0].xyz;
  v_m1 = a_model[1].xyz;
  v_m2 = a_model[2].xyz;
#else
  vec3 world_pos = a_position;
  vec3 unit_normal = len > 1e-20 ? a_normal / len : vec3(0.0);
  uvec2 ids = a_ids;
  uint object_id = u_object_id;
#endif
  vec4 view_pos = u_view * vec4(world_pos, 1.0);
  // The view matrix is rigid, so its upper 3x3 rotates normals.
  v_normal = mat3(u_view) * unit_normal;
  v_view_pos = view_pos.xyz;
  v_world_pos = world_pos;
  v_uv = a_uv;
  v_color = a_color;
  v_id = u_id_kind == 0 ? ids.x : (u_id_kind == 1 ? ids.y : (u_id_kind == 2 ? object_id : u_object_id));
  v_role = a_role;
  gl_Position = u_proj * view_pos;
  // Every vertex of a triangle carries its cluster, so moving them all outside the clip
  // volume drops the triangle before rasterisation.
  if (u_only_cluster != 0u && ids.y != u_only_cluster) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
}
)GLSL";

const char* const kFragmentBody = R"GLSL(
in vec3 v_view_pos;
in vec3 v_world_pos;
in vec3 v_normal;
in float v_ka;
in vec2 v_uv;
in vec4 v_color;
flat in uint v_id;
flat in uint v_role;
#ifdef INSTANCED
flat in uint v_plant;       // the instance's plant
in vec3 v_plant_pos;        // plant-space position
flat in vec3 v_m0, v_m1, v_m2;  // the instance transform's 3x3 columns
struct AoShell {
  vec4 centre;  // w: volume scale |det L|
  vec4 anchor;
  vec4 inverse[3];
  vec4 transpose[3];
};
layout(std430, binding = 0) readonly buffer AoShellBuffer { AoShell ao_shells[]; };
layout(std430, binding = 1) readonly buffer AoPlantBuffer { uvec4 ao_plants[]; };
layout(std430, binding = 2) readonly buffer AoCrownBuffer { vec4 ao_crowns[]; };
layout(std430, binding = 3) readonly buffer AoGridBuffer { uint ao_grid[]; };
uniform vec4 u_ao_grid;         // x and z of the grid's corner, cell size (<= 0: no crowns)
uniform ivec2 u_ao_grid_cells;  // cells along x and z
#endif

uniform vec4 u_base_color;      // linear RGBA factor
uniform bool u_has_texture;
uniform sampler2D u_texture;    // GL_SRGB8_ALPHA8: sampled values are linear
uniform float u_alpha_cutoff;   // ALPHA_TEST variant: MASK (and BLEND, drawn as MASK)
uniform bool u_double_sided;
uniform bool u_oriented_foliage;  // realigned foliage normals face outward: never flip them
uniform bool u_has_normals;     // false: flat normals from screen-space derivatives
uniform bool u_ortho;
uniform bool u_scaled_normals;  // Luft Fig. 7c: the normal target keeps |N| = ka
uniform bool u_flat_albedo;     // albedo target: the texture's mean colour, not its texels
uniform vec3 u_texture_mean;    // linear mean colour of the bound texture's opaque texels

uniform float u_ambient;
uniform int u_light_count;
uniform vec4 u_light_vector[8]; // view space; w = 0 direction toward the light, 1 position
uniform vec3 u_light_color[8];  // linear intensity
uniform vec2 u_light_spec[8];   // (specular weight, shininess)
uniform mat4 u_view;

// Ambient visibility (AoShading in rasterizer.h): 0 none, 1 constant, 2 ka, 3 Hegeman shells.
uniform int u_ao_model;
uniform float u_ao_constant;
uniform float u_ao_alpha_rho;
uniform int u_ao_shell_count;
uniform vec3 u_ao_centre[64];
uniform vec3 u_ao_anchor[64];
uniform mat3 u_ao_inverse[64];    // L^-1: world -> the shell's unit ball
uniform mat3 u_ao_transpose[64];  // L^T: world normal -> plane normal in the unit ball
uniform float u_ao_volume_scale[64];  // |det L|
uniform vec4 u_ao_crown;              // Eq. 7-8 occluder: centre, radius (<= 0: none)
uniform int u_ao_exact_solid_angle;   // 1: 2 pi (1 - cos beta); 0: the paper's pi (r/d)^2
uniform vec2 u_ao_grass;              // Eq. 9: y of the roots, field height h (<= 0: none)
uniform vec2 u_ao_ground;             // a flat ground: its y, and 1 (0: no ground plane)

#ifdef OUT_COLOR
layout(location = 0) out vec4 o_color;
#endif
#ifdef OUT_NORMAL
layout(location = 1) out vec4 o_normal;
#endif
#ifdef OUT_DEPTH
layout(location = 2) out float o_depth;
#endif
#ifdef OUT_POSITION
layout(location = 3) out vec4 o_position;
#endif
#ifdef OUT_ID
layout(location = 4) out uint o_id;
#endif
#ifdef OUT_KA
layout(location = 5) out float o_ka;
#endif
#ifdef OUT_ALBEDO
layout(location = 6) out vec4 o_albedo;
#endif
#ifdef OUT_AO
layout(location = 7) out float o_ao;
#endif

vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

vec3 surface_normal() {
  if (!u_has_normals) {
    // Flat normal from screen-space derivatives: always faces the viewer, no flip needed.
    return normalize(cross(dFdx(v_view_pos), dFdy(v_view_pos)));
  }
  float len = length(v_normal);
  vec3 n = len > 1e-12 ? v_normal / len : vec3(0.0, 0.0, 1.0);
  const bool keep = u_oriented_foliage && v_role == 0u;  // Role::Foliage
  return u_double_sided && !gl_FrontFacing && !keep ? -n : n;
}

)GLSL";

// The ambient visibility functions (shader_ao.cpp) go between the two halves.
const char* const kFragmentMain = R"GLSL(
void main() {
  vec4 base = u_base_color * v_color;
#if defined(OUT_COLOR) || defined(OUT_ALBEDO)
  if (u_has_texture) base *= texture(u_texture, v_uv);
#elif defined(ALPHA_TEST)
  if (u_has_texture) base.a *= texture(u_texture, v_uv).a;
#endif
#ifdef ALPHA_TEST
  if (base.a < u_alpha_cutoff) discard;
#endif
  vec3 n = surface_normal();

#ifdef OUT_COLOR
  // Luft et al. Eq. 1 (no shadowing term): I = Ia ka + sum_i Ii [kd (N.L) + ks (N.H)^n],
  // Blinn's half vector in place of Phong's reflection vector. Point lights do not attenuate.
  vec3 v = u_ortho ? vec3(0.0, 0.0, 1.0) : normalize(-v_view_pos);
  float ambient = u_ambient * clamp(v_ka, 0.0, 1.0);
  // AO multiplies the ambient term; with model none (0) the colour is exactly as without AO,
  // and with ka (2) the AO is ka itself, already applied.
  if (u_ao_model == 1 || u_ao_model == 3) ambient *= ambient_visibility(n);
  vec3 diffuse = vec3(ambient);
  vec3 specular = vec3(0.0);
  for (int i = 0; i < u_light_count; ++i) {
    vec3 l = u_light_vector[i].xyz;
    if (u_light_vector[i].w != 0.0) {  // point light: no attenuation, just its direction
      vec3 to_light = l - v_view_pos;
      float len = length(to_light);
      l = len > 1e-12 ? to_light / len : n;
    }
    float n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) continue;
    diffuse += n_dot_l * u_light_color[i];
    vec3 h = l + v;  // zero only when the light is exactly behind the surface, seen head-on
    float h_len = length(h);
    if (h_len > 1e-6) {
      float n_dot_h = max(dot(n, h / h_len), 0.0);
      specular += u_light_spec[i].x * pow(n_dot_h, u_light_spec[i].y) * u_light_color[i];
    }
  }
  o_color = vec4(srgb_encode(base.rgb * diffuse + specular), 1.0);
#endif
#ifdef OUT_NORMAL
  o_normal = vec4(u_scaled_normals ? n * clamp(v_ka, 0.0, 1.0) : n, 0.0);
#endif
#ifdef OUT_DEPTH
  o_depth = -v_view_pos.z;
#endif
#ifdef OUT_POSITION
  o_position = vec4(v_view_pos, 1.0);
#endif
#ifdef OUT_ID
  o_id = v_id;
#endif
#ifdef OUT_KA
  o_ka = clamp(v_ka, 0.0, 1.0);  // interpolating 1.0 can round to 1.0000001
#endif
#ifdef OUT_ALBEDO
  vec3 albedo = base.rgb;
  if (u_flat_albedo)
    albedo = (u_base_color * v_color).rgb * (u_has_texture ? u_texture_mean : vec3(1.0));
  o_albedo = vec4(srgb_encode(albedo), 1.0);
#endif
#ifdef OUT_AO
  o_ao = ambient_visibility(n);
#endif
}
)GLSL";

std::string info_log(GLuint object, bool is_program) {
  GLint length = 0;
  if (is_program) {
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  } else {
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  }
  std::vector<char> log(static_cast<size_t>(std::max(length, 1)), '\0');
  if (is_program) {
    glGetProgramInfoLog(object, length, nullptr, log.data());
  } else {
    glGetShaderInfoLog(object, length, nullptr, log.data());
  }
  return std::string(log.data());
}

}  // namespace

std::string raster_vertex_source(bool instanced) {
  return std::string("#version 450 core\n") + (instanced ? "#define INSTANCED 1\n" : "") +
         kVertexBody;
}

std::string raster_fragment_source(TargetMask targets, bool alpha_test, bool instanced) {
  std::string s = "#version 450 core\n";
  if (alpha_test) s += "#define ALPHA_TEST 1\n";
  if (instanced) s += "#define INSTANCED 1\n";
  for (Target t : kAllTargets) {
    if (!has(targets, t)) continue;
    std::string name = target_name(t);
    for (char& c : name)
      c = static_cast<char>(c - 'a' + 'A');
    s += "#define OUT_" + name + " 1\n";
  }
  return s + kFragmentBody + raster_ao_glsl() + kFragmentMain;
}

GLuint compile_shader(GLenum stage, const std::string& source, const std::string& name) {
  GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(shader, false);
    glDeleteShader(shader);
    throw std::runtime_error("GLSL compile error in " + name + ": " + log);
  }
  return shader;
}

GLuint link_program(GLuint vertex, GLuint fragment, const std::string& name) {
  GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = info_log(program, true);
    glDeleteProgram(program);
    throw std::runtime_error("GLSL link error in " + name + ": " + log);
  }
  return program;
}

GLuint build_raster_program(TargetMask targets, bool alpha_test, bool instanced) {
  const std::string name = "raster pass (targets " + std::to_string(targets) +
                           (alpha_test ? ", alpha test" : "") + (instanced ? ", instanced)" : ")");
  GLuint vs = compile_shader(GL_VERTEX_SHADER, raster_vertex_source(instanced), name + " vertex");
  GLuint fs = 0;
  try {
    fs = compile_shader(GL_FRAGMENT_SHADER, raster_fragment_source(targets, alpha_test, instanced),
                        name + " fragment");
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return link_program(vs, fs, name);
}

RasterProgram make_raster_program(TargetMask targets, bool alpha_test, bool instanced) {
  RasterProgram p;
  p.id = build_raster_program(targets, alpha_test, instanced);
  auto loc = [&](const char* name) { return glGetUniformLocation(p.id, name); };
  p.view = loc("u_view");
  p.proj = loc("u_proj");
  p.id_kind = loc("u_id_kind");
  p.only_cluster = loc("u_only_cluster");
  p.object_id = loc("u_object_id");
  p.branch_cluster = loc("u_branch_cluster");
  p.base_color = loc("u_base_color");
  p.has_texture = loc("u_has_texture");
  p.texture = loc("u_texture");
  p.alpha_cutoff = loc("u_alpha_cutoff");
  p.double_sided = loc("u_double_sided");
  p.oriented_foliage = loc("u_oriented_foliage");
  p.has_normals = loc("u_has_normals");
  p.ortho = loc("u_ortho");
  p.scaled_normals = loc("u_scaled_normals");
  p.flat_albedo = loc("u_flat_albedo");
  p.texture_mean = loc("u_texture_mean");
  p.ambient = loc("u_ambient");
  p.light_count = loc("u_light_count");
  p.light_vector = loc("u_light_vector");
  p.light_color = loc("u_light_color");
  p.light_spec = loc("u_light_spec");
  p.ao_model = loc("u_ao_model");
  p.ao_constant = loc("u_ao_constant");
  p.ao_alpha_rho = loc("u_ao_alpha_rho");
  p.ao_shell_count = loc("u_ao_shell_count");
  p.ao_centre = loc("u_ao_centre");
  p.ao_anchor = loc("u_ao_anchor");
  p.ao_inverse = loc("u_ao_inverse");
  p.ao_transpose = loc("u_ao_transpose");
  p.ao_volume_scale = loc("u_ao_volume_scale");
  p.ao_crown = loc("u_ao_crown");
  p.ao_exact_solid_angle = loc("u_ao_exact_solid_angle");
  p.ao_grass = loc("u_ao_grass");
  p.ao_ground = loc("u_ao_ground");
  p.ao_grid = loc("u_ao_grid");
  p.ao_grid_cells = loc("u_ao_grid_cells");
  return p;
}

}  // namespace sylva
