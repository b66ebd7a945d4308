#include "npr/ao_reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.h"
#include "npr/ao_fit.h"
#include "npr/ao_pass.h"
#include "npr/ao_shells.h"
#include "npr/hegeman_ao.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

struct Soup {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  void add_triangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const uint32_t base = uint32_t(positions.size());
    positions.insert(positions.end(), {a, b, c});
    indices.insert(indices.end(), {base, base + 1, base + 2});
  }
  // Quad a-b-c-d (counter-clockwise) as two triangles sharing the diagonal a-c.
  void add_quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    add_triangle(a, b, c);
    add_triangle(a, c, d);
  }
};

// Horizontal square [x0, x1] x [z0, z1] at height y.
void add_square(Soup& s, float x0, float x1, float z0, float z1, float y) {
  s.add_quad(glm::vec3(x0, y, z0), glm::vec3(x1, y, z0), glm::vec3(x1, y, z1),
             glm::vec3(x0, y, z1));
}

Soup closed_cube(float h) {
  Soup s;
  const glm::vec3 c[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                          {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
  for (const auto& f : faces)
    s.add_quad(c[f[0]], c[f[1]], c[f[2]], c[f[3]]);
  return s;
}

// `count` equilateral triangles of side `side`, centres uniform in the ball of `radius`
// around the origin, orientations uniform: the uniform random leaf sphere of Hegeman §3.
Soup leaf_sphere(size_t count, float radius, float side, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> g(0.0f, 1.0f);
  Soup s;
  while (s.indices.size() < 3 * count) {
    const glm::vec3 c(u(rng), u(rng), u(rng));
    if (glm::dot(c, c) > 1.0f) continue;
    glm::vec3 n(g(rng), g(rng), g(rng)), t(g(rng), g(rng), g(rng));
    if (glm::length(n) < 1e-3f) continue;
    n = glm::normalize(n);
    t -= glm::dot(t, n) * n;
    if (glm::length(t) < 1e-3f) continue;
    t = glm::normalize(t);
    const glm::vec3 b = glm::cross(n, t);
    const float r = side / std::sqrt(3.0f);  // circumradius
    const glm::vec3 centre = radius * c;
    s.add_triangle(centre + r * t, centre + r * (-0.5f * t + 0.8660254f * b),
                   centre + r * (-0.5f * t - 0.8660254f * b));
  }
  return s;
}

void random_queries(size_t n, float radius, uint32_t seed, std::vector<glm::vec3>& points,
                    std::vector<glm::vec3>& normals) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::normal_distribution<float> g(0.0f, 1.0f);
  while (points.size() < n) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    const glm::vec3 d(g(rng), g(rng), g(rng));
    if (glm::dot(p, p) > 1.0f || glm::length(d) < 1e-3f) continue;
    points.push_back(radius * p);
    normals.push_back(glm::normalize(d));
  }
}

AoReferenceOptions rays(int n, uint64_t seed = 1, int threads = 0) {
  AoReferenceOptions o;
  o.rays = n;
  o.seed = seed;
  o.threads = threads;
  return o;
}

TEST(AoReference, Validation) {
  const AoReferenceScene scene({}, {});
  const glm::vec3 p(0), n(0, 1, 0);
  EXPECT_NO_THROW(scene.visibility_at(p, n, rays(1), 0));
  EXPECT_NO_THROW(scene.visibility_at(p, n, rays(4096), 0));
  EXPECT_THROW(scene.visibility_at(p, n, rays(0), 0), InputError);
  EXPECT_THROW(scene.visibility_at(p, n, rays(4097), 0), InputError);
  AoReferenceOptions o;
  o.origin_offset = -1.0f;
  EXPECT_THROW(validate_ao_reference(o), InputError);
  o.origin_offset = NAN;
  EXPECT_THROW(validate_ao_reference(o), InputError);
  EXPECT_THROW(validate_ao_reference(rays(8, 1, -1)), InputError);
  try {
    validate_ao_reference(rays(0));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "ao-rays");
  }
  EXPECT_THROW(AoReferenceScene({glm::vec3(0), glm::vec3(1), glm::vec3(NAN)}, {0, 1, 2}),
               InputError);
  EXPECT_EQ(scene.visibility_at(p, n, rays(16), 0), 1.0f);  // empty scene: open sky
}

TEST(AoReference, ClosedBoxBlocksEverything) {
  const Soup box = closed_cube(1.0f);
  const AoReferenceScene scene(box.positions, box.indices);
  EXPECT_EQ(scene.triangle_count(), 12u);
  for (int n : {1, 7, 64, 1000})
    for (const glm::vec3& normal : {glm::vec3(0, 1, 0), glm::vec3(0.3f, -0.2f, 0.9f), glm::vec3(0)})
      EXPECT_EQ(scene.visibility_at(glm::vec3(0.1f, 0.2f, -0.3f), normal, rays(n), 3), 0.0f);
  // Outside, facing away: nothing in the hemisphere.
  EXPECT_EQ(scene.visibility_at(glm::vec3(0, 2, 0), glm::vec3(0, 1, 0), rays(256), 0), 1.0f);
  EXPECT_EQ(scene.visibility_at(glm::vec3(NAN), glm::vec3(0, 1, 0), rays(8), 0), 1.0f);
}

TEST(AoReference, GroundPlaneHalvesAHorizontalNormal) {
  // 0.1 below: more than the auto origin offset of a scene 2.8 km across (about 4 cm).
  Soup ground;
  add_square(ground, -1e3f, 1e3f, -1e3f, 1e3f, -0.1f);
  const AoReferenceScene scene(ground.positions, ground.indices);
  EXPECT_EQ(scene.visibility_at(glm::vec3(0), glm::vec3(0, 1, 0), rays(256), 0), 1.0f);
  EXPECT_EQ(scene.visibility_at(glm::vec3(0), glm::vec3(0, -1, 0), rays(256), 0), 0.0f);
  EXPECT_NEAR(scene.visibility_at(glm::vec3(0), glm::vec3(1, 0, 0), rays(1024), 0), 0.5f, 0.01f);
  EXPECT_NEAR(scene.visibility_at(glm::vec3(0), glm::vec3(0), rays(1024), 0), 0.5f, 0.01f);
}

TEST(AoReference, UniformNotCosineWeighted) {
  // A square of side 2 one unit above: solid angle 4 asin(1/2) = 2 pi / 3, so the uniform
  // hemisphere average is 2/3; a cosine-weighted estimate would give ~0.446.
  Soup roof;
  add_square(roof, -1.0f, 1.0f, -1.0f, 1.0f, 1.0f);
  const AoReferenceScene scene(roof.positions, roof.indices);
  const double expected = 1.0 - 4.0 * std::asin(0.5) / (2.0 * kPi);
  EXPECT_NEAR(scene.visibility_at(glm::vec3(0), glm::vec3(0, 1, 0), rays(4096), 0), expected,
              0.005);
}

TEST(AoReference, NoSelfHitsOnTheQueryLeaf) {
  Soup leaf;
  leaf.add_triangle(glm::vec3(-1, 0, -1), glm::vec3(1, 0, -1), glm::vec3(0, 0, 1));
  add_square(leaf, 10.0f, 11.0f, 10.0f, 11.0f, 0.0f);  // far away, edge-on: scene scale
  const AoReferenceScene scene(leaf.positions, leaf.indices);
  EXPECT_GT(scene.auto_origin_offset(), 0.0f);
  EXPECT_LT(scene.auto_origin_offset(), 1e-3f);
  const glm::vec3 on_leaf(0.0f, 0.0f, -1.0f / 3.0f);
  EXPECT_EQ(scene.visibility_at(on_leaf, glm::vec3(0, 1, 0), rays(512), 0), 1.0f);
  EXPECT_EQ(scene.visibility_at(on_leaf, glm::vec3(0, -1, 0), rays(512), 0), 1.0f);
}

// make_scene_tracer reads the scene's materials: a roof quad over the point lets rays through
// where its base-colour texture's alpha is below the cutoff (MASK: the material's cutoff;
// BLEND: 0.5) and blocks elsewhere; an opaque material blocks whatever its texture holds.
TEST(AoReference, SceneTracerHonoursAlphaCutoutTextures) {
  auto visibility = [](uint8_t alpha, AlphaMode mode, float cutoff, bool half = false) {
    Scene s;
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba = {200, 200, 200, alpha, 200, 200, 200, half ? uint8_t(255) : alpha};
    s.textures.push_back(t);
    Material m;
    m.base_color_texture = 0;
    m.alpha_mode = mode;
    m.alpha_cutoff = cutoff;
    s.materials.push_back(m);
    Mesh roof;
    roof.material = 0;
    roof.positions = {{-2, 1, -2}, {2, 1, -2}, {2, 1, 2}, {-2, 1, 2}};
    roof.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // u = 0.5 splits the roof at x = 0
    roof.indices = {0, 1, 2, 0, 2, 3};
    s.meshes.push_back(roof);
    const AoReferenceScene tracer = make_scene_tracer(s);
    AoReferenceOptions o;
    o.rays = 1024;
    return tracer.visibility({glm::vec3(0)}, {glm::vec3(0, 1, 0)}, o)[0];
  };
  const float blocked = visibility(255, AlphaMode::Opaque, 0.5f);
  EXPECT_LT(blocked, 0.6f);
  EXPECT_GT(blocked, 0.0f);
  EXPECT_EQ(visibility(0, AlphaMode::Opaque, 0.5f), blocked);  // opaque ignores the texture
  EXPECT_EQ(visibility(0, AlphaMode::Mask, 0.5f), 1.0f);
  EXPECT_EQ(visibility(255, AlphaMode::Mask, 0.5f), blocked);
  EXPECT_EQ(visibility(100, AlphaMode::Mask, 0.5f), 1.0f);        // 0.39 < 0.5
  EXPECT_EQ(visibility(100, AlphaMode::Mask, 0.3f), blocked);     // 0.39 >= 0.3
  EXPECT_EQ(visibility(100, AlphaMode::Blend, 0.3f), 1.0f);       // BLEND cuts at 0.5
  const float half = visibility(0, AlphaMode::Mask, 0.5f, true);  // one half of the roof
  EXPECT_GT(half, blocked + 0.1f);
  EXPECT_LT(half, 0.95f);
}

TEST(AoReference, FilterAndAlphaCutout) {
  const Soup box = closed_cube(1.0f);
  const AoReferenceScene open(box.positions, box.indices,
                              [](uint32_t, float, float) { return false; });
  EXPECT_EQ(open.visibility_at(glm::vec3(0), glm::vec3(0, 1, 0), rays(64), 0), 1.0f);

  // A roof whose texture is transparent for x < 0 equals a roof over x >= 0 only.
  Soup roof;
  add_square(roof, -1.0f, 1.0f, -1.0f, 1.0f, 1.0f);
  std::vector<glm::vec2> uvs;
  for (const glm::vec3& p : roof.positions)
    uvs.emplace_back((p.x + 1) / 2, (p.z + 1) / 2);
  const auto alpha = [](uint32_t, glm::vec2 uv) { return uv.x >= 0.5f ? 1.0f : 0.0f; };
  const AoReferenceScene cut(roof.positions, roof.indices,
                             make_alpha_cutout_filter(uvs, roof.indices, alpha, 0.5f));
  Soup half;
  add_square(half, 0.0f, 1.0f, -1.0f, 1.0f, 1.0f);
  const AoReferenceScene geometric(half.positions, half.indices);
  const glm::vec3 n(0.2f, 1.0f, 0.1f);
  const float v_cut = cut.visibility_at(glm::vec3(0), n, rays(2048), 5);
  EXPECT_NEAR(v_cut, geometric.visibility_at(glm::vec3(0), n, rays(2048), 5), 2.0f / 2048.0f);
  const float v_full =
      AoReferenceScene(roof.positions, roof.indices).visibility_at(glm::vec3(0), n, rays(2048), 5);
  EXPECT_GT(v_cut, v_full + 0.1f);
  // Triangles outside the cutout set always block.
  const AoReferenceScene solid(
      roof.positions, roof.indices,
      make_alpha_cutout_filter(uvs, roof.indices, alpha, 0.5f, [](uint32_t) { return false; }));
  EXPECT_EQ(solid.visibility_at(glm::vec3(0), n, rays(2048), 5), v_full);
}

TEST(AoReference, OneRay) {
  const Soup sphere = leaf_sphere(2000, 1.0f, 0.1f, 3);
  const AoReferenceScene scene(sphere.positions, sphere.indices);
  std::vector<glm::vec3> pts, nrm;
  random_queries(200, 0.9f, 4, pts, nrm);
  const std::vector<float> v = scene.visibility(pts, nrm, rays(1));
  int zeros = 0;
  for (float x : v) {
    ASSERT_TRUE(x == 0.0f || x == 1.0f);
    zeros += x == 0.0f;
  }
  EXPECT_GT(zeros, 0);
  EXPECT_LT(zeros, 200);
}

TEST(AoReference, DeterministicForAnyThreadCount) {
  const Soup sphere = leaf_sphere(5000, 1.0f, 0.06f, 5);
  const AoReferenceScene scene(sphere.positions, sphere.indices);
  std::vector<glm::vec3> pts, nrm;
  random_queries(3000, 1.0f, 6, pts, nrm);
  nrm[7] = glm::vec3(0.0f);
  const auto a = scene.visibility(pts, nrm, rays(32, 9, 2));
  const auto b = scene.visibility(pts, nrm, rays(32, 9, 2));
  const auto one = scene.visibility(pts, nrm, rays(32, 9, 1));
  ASSERT_EQ(a.size(), pts.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(a.data(), one.data(), a.size() * sizeof(float)));
  EXPECT_EQ(a[11], scene.visibility_at(pts[11], nrm[11], rays(32, 9), 11));
  EXPECT_NE(a, scene.visibility(pts, nrm, rays(32, 10, 2)));  // another seed
  for (float v : a)
    ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
}

// Hegeman §3 on its own assumptions: leaves uniform in a sphere of radius R, a Poisson field
// with extinction sigma = leaves per volume * mean projected area (half a two-sided leaf's
// area). Its ensemble visibility is the hemisphere average of exp(-sigma L), L the chord
// from x to the sphere, so exp(-sigma R) at the centre for every normal: alpha_rho =
// sigma R / (2/3 pi R_shell^3) makes Eq. 6 exact there.
struct LeafSphereCase {
  static constexpr float kRadius = 1.0f;
  static constexpr size_t kLeaves = 20000;
  static constexpr float kSide = 0.031f;  // sigma R ~ 1: V = 0.37 at the centre
  Soup crown = leaf_sphere(kLeaves, kRadius, kSide, 7);
  AoReferenceScene scene{crown.positions, crown.indices};
  Sphere shell = fit_bounding_sphere(crown.positions);
  double sigma = double(kLeaves) / (4.0 / 3.0 * kPi * std::pow(double(kRadius), 3.0)) *
                 (std::sqrt(3.0) / 4.0 * kSide * kSide) / 2.0;
  double centre_alpha_rho =
      sigma * kRadius / (2.0 / 3.0 * kPi * std::pow(double(shell.radius), 3.0));

  static const LeafSphereCase& get() {
    static const LeafSphereCase c;
    return c;
  }
  // The ensemble visibility by quadrature over the hemisphere (uniform in cos theta, phi).
  double poisson_visibility(glm::dvec3 x, glm::dvec3 n) const {
    const glm::dvec3 t = glm::normalize(
        glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(n, t);
    const int steps = 40;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i)
      for (int j = 0; j < steps; ++j) {
        const double z = (i + 0.5) / steps, phi = 2.0 * kPi * (j + 0.5) / steps;
        const double r = std::sqrt(1.0 - z * z);
        const glm::dvec3 w = r * std::cos(phi) * t + r * std::sin(phi) * b + z * n;
        const double p = glm::dot(x, w), q = glm::dot(x, x) - double(kRadius) * kRadius;
        sum += std::exp(-sigma * (-p + std::sqrt(std::max(0.0, p * p - q))));
      }
    return sum / (steps * steps);
  }
};

double rmse(const std::vector<double>& a, const std::vector<float>& b) {
  double se = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    se += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(se / double(a.size()));
}

TEST(AoReference, MatchesThePoissonVisibilityOfAUniformLeafSphere) {
  const LeafSphereCase& c = LeafSphereCase::get();
  std::vector<glm::vec3> pts, nrm;
  random_queries(1000, 0.97f * c.kRadius, 8, pts, nrm);
  const std::vector<float> reference = c.scene.visibility(pts, nrm, rays(1024, 3));
  std::vector<double> poisson;
  double bias = 0.0;
  for (size_t i = 0; i < pts.size(); ++i) {
    poisson.push_back(c.poisson_visibility(pts[i], nrm[i]));
    bias += (reference[i] - poisson.back()) / double(pts.size());
  }
  // What remains with many rays (~0.042) is the spread of one leaf layout around the
  // ensemble: leaves near a point cover large solid angles. The mean agrees.
  const double err = rmse(poisson, reference);
  std::printf("uniform leaf sphere: reference vs Poisson visibility RMSE %.4f, bias %.4f\n", err,
              bias);
  EXPECT_LT(err, 0.05);
  EXPECT_LT(std::abs(bias), 0.01);
}

TEST(AoReference, FittedHegemanSphereOnAUniformLeafSphere) {
  const LeafSphereCase& c = LeafSphereCase::get();
  EXPECT_NEAR(c.shell.radius, c.kRadius + c.kSide / std::sqrt(3.0f), 0.01f);
  // Near the centre the model is exact, so the fit recovers the analytic alpha_rho.
  std::vector<glm::vec3> pts, nrm;
  random_queries(300, 0.05f * c.kRadius, 9, pts, nrm);
  std::vector<float> reference = c.scene.visibility(pts, nrm, rays(256, 4));
  std::vector<AlphaRhoSample> samples;
  for (size_t i = 0; i < pts.size(); ++i)
    samples.push_back({sphere_cap(c.shell, pts[i], nrm[i]).weighted_volume, reference[i]});
  const AlphaRhoFit centre = fit_alpha_rho(samples);
  EXPECT_NEAR(centre.alpha_rho / c.centre_alpha_rho, 1.0, 0.08);

  // Over the whole crown the model's error is its own: Eq. 6 takes the exponential of an
  // average depth where the truth averages exponentials, so it overstates how much the
  // normal's orientation matters. The bounds record the measured quality.
  pts.clear(), nrm.clear(), samples.clear();
  random_queries(1500, 0.97f * c.kRadius, 10, pts, nrm);
  reference = c.scene.visibility(pts, nrm, rays(256, 5));
  for (size_t i = 0; i < pts.size(); ++i)
    samples.push_back({sphere_cap(c.shell, pts[i], nrm[i]).weighted_volume, reference[i]});
  const AlphaRhoFit fit = fit_alpha_rho(samples);
  std::vector<double> model;
  for (size_t i = 0; i < pts.size(); ++i)
    model.push_back(hegeman_visibility(c.shell, pts[i], nrm[i], float(c.centre_alpha_rho)));
  const double analytic_rmse = rmse(model, reference);
  std::printf(
      "uniform leaf sphere: sigma R = %.3f; alpha_rho fitted at the centre %.4f, over "
      "the crown %.4f, analytic %.4f; RMSE over the crown: fitted %.4f, analytic %.4f\n",
      c.sigma * c.kRadius, centre.alpha_rho, fit.alpha_rho, c.centre_alpha_rho, fit.rmse,
      analytic_rmse);
  EXPECT_NEAR(fit.alpha_rho / c.centre_alpha_rho, 1.0, 0.3);
  EXPECT_LE(fit.rmse, analytic_rmse + 1e-9);  // least squares beats any other alpha_rho
  EXPECT_LT(fit.rmse, 0.2);
}

}  // namespace
}  // namespace sylva
