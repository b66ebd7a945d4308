// The whole Luft preprocessing (npr/foliage_illumination.h) on sample plants, the shared fern
// and synthetic extremes: the paper's qualitative claims (ka lower deep in the crown than on
// its rim, wood under the crown darkened), invariants (finite, unit normals, ka in
// [ka_min, 1]), scale invariance, and every parameter at the ends of its range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/scene/load.h"
#include "npr/foliage_illumination.h"
#include "samples/plants.h"
#include "tests/test_support.h"

namespace sylva::test {
namespace {

const Scene& tree() {
  static const Scene s = [] {
    PlantOptions o;
    o.leaves = 3000;
    o.seed = 4;
    return make_plant(o);
  }();
  return s;
}

FoliageParams params(int grid = 48) {
  FoliageParams p;
  p.grid = grid;
  return p;
}

// Finite, unit normals, ka in [ka_min, 1], one value per vertex.
void expect_valid(const Scene& s, const FoliageIllumination& r, float ka_min) {
  ASSERT_EQ(r.normals.size(), s.meshes.size());
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    ASSERT_EQ(r.normals[m].size(), s.meshes[m].positions.size());
    ASSERT_EQ(r.ka[m].size(), s.meshes[m].positions.size());
    for (size_t v = 0; v < r.normals[m].size(); ++v) {
      const glm::vec3 n = r.normals[m][v];
      ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
      ASSERT_GE(r.ka[m][v], ka_min);
      ASSERT_LE(r.ka[m][v], 1.0f);
    }
  }
  for (const glm::vec3& n : r.surface.normals)
    ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
}

double angle_deg(const glm::vec3& a, const glm::vec3& b) {
  return std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) * 180.0 / M_PI;
}

std::vector<char> foliage_vertices(const Mesh& m) {
  std::vector<char> f(m.positions.size(), 0);
  for (size_t t = 0; t < m.triangle_count(); ++t)
    if (m.roles[t] == Role::Foliage)
      for (int k = 0; k < 3; ++k)
        f[m.indices[3 * t + k]] = 1;
  return f;
}

// A square leaf of side `size` at `c` facing `n`, as its own mesh.
Mesh leaf(glm::vec3 c, glm::vec3 n, float size) {
  n = glm::normalize(n);
  const glm::vec3 a =
      glm::normalize(glm::cross(n, std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
  const glm::vec3 b = glm::cross(n, a);
  const float h = 0.5f * size;
  Mesh m;
  m.positions = {c - h * a - h * b, c + h * a - h * b, c + h * a + h * b, c - h * a + h * b};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Scene foliage_scene(std::vector<Mesh> meshes) {
  Scene s;
  s.meshes = std::move(meshes);
  LoadOptions all;
  all.foliage = "all";
  finish_scene(s, all);
  return s;
}

// Leaves on a jittered lattice filling a ball of radius 1 (a crown without a tree).
Scene leaf_ball(int per_axis, bool flat = false) {
  std::vector<Mesh> leaves;
  uint32_t h = 12345;
  auto rnd = [&h] {
    h = h * 1664525u + 1013904223u;
    return float(h >> 8) / float(1u << 24);
  };
  for (int i = 0; i < per_axis; ++i)
    for (int j = 0; j < per_axis; ++j)
      for (int k = 0; k < (flat ? 1 : per_axis); ++k) {
        glm::vec3 p = (glm::vec3(i, j, k) + 0.5f) / float(per_axis) * 2.0f - 1.0f;
        if (flat) p.z = 0.0f;
        if (glm::length(p) > 1.0f) continue;
        const glm::vec3 n(rnd() - 0.5f, rnd() - 0.5f, flat ? 1.0f : rnd() - 0.5f);
        leaves.push_back(
            leaf(p, glm::length(n) > 1e-3f ? n : glm::vec3(0, 0, 1), 1.5f / float(per_axis)));
      }
  return foliage_scene(std::move(leaves));
}

TEST(FoliageIllumination, KaIsLowerDeepInTheCrownThanOnItsRim) {
  const Scene& s = tree();
  const FoliageIllumination r = compute_foliage_illumination(s, params());
  expect_valid(s, r, 0.2f);
  const Bounds b = s.bounds(Role::Foliage);
  const glm::vec3 c = b.center(), half = 0.5f * (b.max - b.min);
  double deep = 0, rim = 0;
  int n_deep = 0, n_rim = 0;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const std::vector<char> fol = foliage_vertices(s.meshes[m]);
    for (size_t v = 0; v < fol.size(); ++v) {
      if (!fol[v]) continue;
      const float d = glm::length((s.meshes[m].positions[v] - c) / half);  // 0 centre, ~1 rim
      if (d < 0.35f) deep += r.ka[m][v], ++n_deep;
      if (d > 0.85f) rim += r.ka[m][v], ++n_rim;
    }
  }
  ASSERT_GT(n_deep, 50);
  ASSERT_GT(n_rim, 50);
  deep /= n_deep;
  rim /= n_rim;
  std::printf("mean ka deep %.3f (%d vertices), rim %.3f (%d)\n", deep, n_deep, rim, n_rim);
  EXPECT_LT(deep + 0.2, rim);
}

TEST(FoliageIllumination, WoodUnderTheCrownIsDarkenedAndTheBaseIsNot) {
  const Scene& s = tree();
  const FoliageIllumination r = compute_foliage_illumination(s, params());
  const Bounds b = s.bounds(Role::Foliage);
  const float rho = float(r.stats.rho);
  double inside = 0;
  int n_inside = 0, n_base = 0;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    const Mesh& mesh = s.meshes[m];
    const std::vector<char> fol = foliage_vertices(mesh);
    for (size_t v = 0; v < fol.size(); ++v) {
      if (fol[v]) continue;
      const glm::vec3 p = mesh.positions[v];
      if (p.y < b.min.y - rho) {  // trunk below the crown's reach: F = -tau, ka = 1
        EXPECT_EQ(r.ka[m][v], 1.0f);
        ++n_base;
      } else if (glm::all(glm::greaterThan(p, b.min)) && glm::all(glm::lessThan(p, b.max)) &&
                 glm::length(glm::vec2(p.x, p.z) - glm::vec2(b.center().x, b.center().z)) <
                     0.25f * (b.max.x - b.min.x)) {
        inside += r.ka[m][v];
        ++n_inside;
      }
    }
  }
  ASSERT_GE(n_base, 4);
  ASSERT_GT(n_inside, 50);
  std::printf("wood inside the crown: mean ka %.3f (%d vertices)\n", inside / n_inside, n_inside);
  EXPECT_LT(inside / n_inside, 0.7);
}

TEST(FoliageIllumination, ResultsScaleWithTheScene) {
  const Scene& s = tree();
  const FoliageIllumination ref = compute_foliage_illumination(s, params());
  for (float scale : {1e-4f, 1e4f}) {
    Scene t = s;
    for (Mesh& m : t.meshes)
      for (glm::vec3& p : m.positions)
        p *= scale;
    const FoliageIllumination r = compute_foliage_illumination(t, params());
    expect_valid(t, r, 0.2f);
    EXPECT_NEAR(r.stats.rho / scale, ref.stats.rho, 1e-4 * ref.stats.rho);
    EXPECT_NEAR(r.stats.tau, ref.stats.tau, 1e-4 * ref.stats.tau);
    std::vector<double> angles;
    double ka_worst = 0;
    for (size_t m = 0; m < s.meshes.size(); ++m)
      for (size_t v = 0; v < s.meshes[m].positions.size(); ++v) {
        angles.push_back(angle_deg(r.normals[m][v], ref.normals[m][v]));
        ka_worst = std::max(ka_worst, double(std::abs(r.ka[m][v] - ref.ka[m][v])));
      }
    std::sort(angles.begin(), angles.end());
    const double mean = std::accumulate(angles.begin(), angles.end(), 0.0) / double(angles.size());
    const double p99 = angles[angles.size() * 99 / 100];
    std::printf("scale %g: mean normal change %.4f deg, p99 %.4f deg, worst ka change %.2e\n",
                double(scale), mean, p99, ka_worst);
    EXPECT_LT(mean, 0.1) << scale;
    EXPECT_LT(p99, 1.0) << scale;
    EXPECT_LT(ka_worst, 1e-3) << scale;
  }
}

TEST(FoliageIllumination, SamplesAndFernGiveValidShading) {
  std::vector<Scene> scenes;
  for (PlantKind k : {PlantKind::Tree, PlantKind::Bush, PlantKind::Conifer}) {
    PlantOptions o;
    o.kind = k;
    o.leaves = 1500;
    scenes.push_back(make_plant(o));
  }
  scenes.push_back(load_scene(fern_path()));
  for (const Scene& s : scenes) {
    for (NormalSource src : {NormalSource::Surface, NormalSource::Gradient}) {
      FoliageParams p = params(40);
      p.normals = src;
      const FoliageIllumination r = compute_foliage_illumination(s, p);
      expect_valid(s, r, p.ambient.ka_min);
      EXPECT_GT(r.stats.density_max, 0.0);
    }
  }
}

// Every parameter at the ends of its range gives valid shading.
TEST(FoliageIllumination, ParameterExtremes) {
  const Scene& s = tree();
  auto run = [&](FoliageParams p) {
    SCOPED_TRACE("grid " + std::to_string(p.grid));
    const FoliageIllumination r = compute_foliage_illumination(s, p);
    expect_valid(s, r, p.ambient.ka_min);
    return r;
  };
  FoliageParams p = params();
  p.tau = 0.0f;  // every point with a generator in reach is inside
  run(p);
  p = params(128);
  p.rho = SceneLength::parse("1%", "rho");  // isolated blobs around single leaves
  EXPECT_GT(run(p).surface.triangle_count(), 1000u);
  p = params(16);
  p.rho = SceneLength::parse("1000%", "rho");  // one ellipsoid around everything
  run(p);
  p = params();
  p.fraction = 1e-4;  // a single generator
  const FoliageIllumination few = run(p);
  EXPECT_EQ(few.stats.generators, 1u);
  p = params(2);
  p.rho = SceneLength::parse("500%", "rho");
  run(p);
  p = params();
  p.ambient.exponent = 1e-3f;
  run(p);
  p.ambient.exponent = 100.0f;
  run(p);
  p = params();
  p.d_min_auto = false;
  p.ambient.d_min = 1e-6f;  // every inside vertex at ka_min
  const FoliageIllumination dark = run(p);
  size_t at_min = 0, total = 0;
  for (const auto& ka : dark.ka)
    for (float k : ka)
      at_min += k == p.ambient.ka_min, ++total;
  EXPECT_GT(at_min, total / 2);
  p = params();
  p.ambient.ka_min = 0.0f;
  run(p);
  p.ambient.ka_min = 1.0f;  // no ambient darkening at all
  for (const auto& ka : run(p).ka)
    for (float k : ka)
      ASSERT_EQ(k, 1.0f);
  p = params();
  p.blend = 0.0f;  // the model's own normals
  const FoliageIllumination own = run(p);
  for (size_t m = 0; m < s.meshes.size(); ++m)
    for (size_t v = 0; v < s.meshes[m].positions.size(); ++v)
      ASSERT_LT(angle_deg(own.normals[m][v], glm::normalize(s.meshes[m].normals[v])), 0.05);
}

TEST(FoliageIllumination, DegenerateCrowns) {
  // One leaf: a small ellipsoid around it.
  Scene one = foliage_scene({leaf({0, 0, 0}, {0, 0, 1}, 1.0f)});
  FoliageIllumination r = compute_foliage_illumination(one, params(24));
  expect_valid(one, r, 0.2f);
  EXPECT_GT(r.surface.triangle_count(), 10u);
  // Ten coincident leaves: one generator position, weight ten.
  std::vector<Mesh> same(10, leaf({1, 2, 3}, {0, 1, 0}, 0.5f));
  Scene stack = foliage_scene(same);
  r = compute_foliage_illumination(stack, params(24));
  expect_valid(stack, r, 0.2f);
  // A flat planar crown: zero extent along z, padded by rho.
  Scene flat = leaf_ball(12, true);
  r = compute_foliage_illumination(flat, params(48));
  expect_valid(flat, r, 0.2f);
  // Its realigned normals point away from the plane near the middle.
  size_t facing = 0, middle = 0;
  for (size_t m = 0; m < flat.meshes.size(); ++m)
    for (size_t v = 0; v < flat.meshes[m].positions.size(); ++v)
      if (glm::length(flat.meshes[m].positions[v]) < 0.4f)
        ++middle, facing += std::abs(r.normals[m][v].z) > 0.8f;
  EXPECT_GT(facing, middle * 9 / 10);
  // A thin row of leaves at grid 512 (a long, thin box keeps the grid small).
  std::vector<Mesh> row;
  for (int i = 0; i < 200; ++i)
    row.push_back(leaf({float(i) * 0.05f, 0, 0}, {0, 1, 0}, 0.04f));
  Scene line = foliage_scene(row);
  FoliageParams p = params(512);
  p.rho = SceneLength::parse("0.1", "rho");
  r = compute_foliage_illumination(line, p);
  expect_valid(line, r, 0.2f);
}

TEST(FoliageIllumination, UniformBallDarkensTowardsItsCentre) {
  // The paper's setting in its simplest form: ka rises monotonically (in shells) from the
  // centre of a uniform leaf ball to its rim.
  const Scene ball = leaf_ball(14);
  const FoliageIllumination r = compute_foliage_illumination(ball, params(48));
  expect_valid(ball, r, 0.2f);
  double shell[4] = {0, 0, 0, 0};
  int count[4] = {0, 0, 0, 0};
  for (size_t m = 0; m < ball.meshes.size(); ++m)
    for (size_t v = 0; v < ball.meshes[m].positions.size(); ++v) {
      const int k = std::min(3, int(glm::length(ball.meshes[m].positions[v]) * 4.0f));
      shell[k] += r.ka[m][v];
      ++count[k];
    }
  for (int k = 0; k < 4; ++k)
    shell[k] /= std::max(count[k], 1);
  std::printf("ka by shell: %.3f %.3f %.3f %.3f\n", shell[0], shell[1], shell[2], shell[3]);
  EXPECT_LE(shell[0], shell[1] + 1e-4);  // both may sit at ka_min
  EXPECT_LT(shell[1], shell[2]);
  EXPECT_LT(shell[2], shell[3]);
}

TEST(FoliageIllumination, EmptySurfaceIsAClearError) {
  FoliageParams p = params();
  p.tau = 1e9f;
  try {
    compute_foliage_illumination(tree(), p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where(), "tau");
    for (const char* word : {"tau", "rho", "spans"})
      EXPECT_NE(what.find(word), std::string::npos) << what;
  }
  Scene wood = tree();
  for (Mesh& m : wood.meshes)
    std::fill(m.roles.begin(), m.roles.end(), Role::Wood);
  EXPECT_THROW(compute_foliage_illumination(wood, params()), InputError);
}

}  // namespace
}  // namespace sylva::test
