// Density field (Luft et al. Eq. 2-3): kernel values, analytic gradient against finite
// differences, the hash grid against a brute-force sum, fill_grid against value() at every
// node, determinism over thread counts, parameter ranges and extremes (tiny/huge rho,
// coincident generators, scaled scenes).
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"
#include "npr/density_field.h"
#include "npr/generators.h"
#include "samples/plants.h"

namespace sylva {
namespace {

std::vector<glm::vec3> random_points(size_t n, uint32_t seed, float extent = 1.0f,
                                     glm::vec3 offset = glm::vec3(0.0f)) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, extent);
  std::vector<glm::vec3> p(n);
  for (glm::vec3& q : p)
    q = offset + glm::vec3(u(rng), u(rng), u(rng));
  return p;
}

// Eq. 2-3 summed over every generator, in double.
double brute_force(const std::vector<glm::vec3>& gens, float rho, float tau, glm::dvec3 q) {
  double sum = 0.0;
  for (const glm::vec3& p : gens) {
    const glm::dvec3 d = q - glm::dvec3(p);
    const double s = glm::dot(d, d) / (double(rho) * double(rho));
    if (s < 1.0) sum += (1.0 - s) * (1.0 - s);
  }
  return sum - tau;
}

// A grid over the generators' bounds padded by rho.
ScalarGrid grid_for(const DensityField& f, int cells) {
  const Bounds b = f.generator_bounds();
  return make_grid(b.min - glm::vec3(f.rho()), b.max + glm::vec3(f.rho()), cells);
}

// |a - b| within `rel` of the density scale at b (the sum of kernels, at least 1).
void expect_close(float a, double b, float tau, double rel, const char* what) {
  EXPECT_NEAR(a, b, rel * std::max(1.0, std::abs(b) + tau)) << what;
}

// Every node of fill_grid equals value() at that node.
void expect_grid_matches_value(const DensityField& f, const ScalarGrid& g) {
  size_t bad = 0;
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        const float a = g.at(x, y, z);
        const float b = f.value(g.position(x, y, z));
        ASSERT_TRUE(std::isfinite(a));
        if (std::abs(a - b) > 1e-5f * std::max(1.0f, std::abs(b) + f.tau())) {
          if (++bad < 5)
            ADD_FAILURE() << "node " << x << "," << y << "," << z << ": grid " << a << " value "
                          << b;
        }
      }
  EXPECT_EQ(bad, 0u);
}

TEST(Density, KernelValues) {
  const float rho = 2.0f, tau = 0.3f;
  const glm::vec3 p(1.0f, -2.0f, 0.5f);
  DensityField f({p}, rho, tau);
  EXPECT_FLOAT_EQ(f.value(p), 1.0f - tau);  // d = 0
  for (glm::vec3 dir : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::normalize(glm::vec3(1))}) {
    EXPECT_NEAR(f.value(p + 0.5f * rho * dir), 0.5625f - tau, 1e-6f);  // (1 - 1/4)^2
    EXPECT_NEAR(f.value(p + rho * dir), -tau, 1e-6f);
    EXPECT_FLOAT_EQ(f.value(p + 1.5f * rho * dir), -tau);
    EXPECT_FLOAT_EQ(f.value(p + 100.0f * rho * dir), -tau);
  }
  glm::vec3 g(1.0f);
  EXPECT_FLOAT_EQ(f.value_and_gradient(p, g), 1.0f - tau);
  EXPECT_EQ(g, glm::vec3(0.0f));
  // grad D = -4 (1 - s) (q - p) / rho^2 with s = 1/4: pointing back at the generator.
  f.value_and_gradient(p + glm::vec3(0.5f * rho, 0, 0), g);
  EXPECT_NEAR(g.x, -4.0f * 0.75f * (0.5f * rho) / (rho * rho), 1e-6f);
  EXPECT_FLOAT_EQ(g.y, 0.0f);
  EXPECT_FLOAT_EQ(f.rho(), rho);
  EXPECT_FLOAT_EQ(f.tau(), tau);
}

TEST(Density, GradientMatchesFiniteDifferences) {
  const std::vector<glm::vec3> gens = random_points(300, 1);
  const float rho = 0.25f;
  DensityField f(gens, rho, 0.5f);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-0.1f, 1.1f);
  const double h = 1e-5;
  int checked = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 q(u(rng), u(rng), u(rng));
    glm::vec3 g;
    const float v = f.value_and_gradient(q, g);
    EXPECT_FLOAT_EQ(v, f.value(q));
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 e(0.0);
      e[k] = h;
      const double fd = (brute_force(gens, rho, 0.5f, glm::dvec3(q) + e) -
                         brute_force(gens, rho, 0.5f, glm::dvec3(q) - e)) /
                        (2.0 * h);
      EXPECT_NEAR(g[k], fd, 1e-4 * std::max(1.0, std::abs(fd))) << "query " << i << " axis " << k;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 900);
}

TEST(Density, ValueEqualsBruteForce) {
  for (float rho : {0.03f, 0.1f, 0.6f}) {
    const std::vector<glm::vec3> gens = random_points(3000, 7, 2.0f, glm::vec3(-1.0f, 3.0f, 0));
    const float tau = 0.25f;
    DensityField f(gens, rho, tau);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    for (int i = 0; i < 400; ++i) {
      const glm::vec3 q = glm::vec3(0.0f, 4.0f, 1.0f) + glm::vec3(u(rng), u(rng), u(rng));
      expect_close(f.value(q), brute_force(gens, rho, tau, q), tau, 1e-6, "random query");
    }
    for (size_t i = 0; i < gens.size(); i += 97)  // at the generators themselves
      expect_close(f.value(gens[i]), brute_force(gens, rho, tau, gens[i]), tau, 1e-6, "at p_i");
  }
}

TEST(Density, FillGridEqualsValueAtEveryNode) {
  const std::vector<glm::vec3> gens = random_points(2000, 3, 1.0f, glm::vec3(10.0f, -5.0f, 2.0f));
  for (float rho : {0.05f, 0.2f}) {
    DensityField f(gens, rho, 0.4f);
    ScalarGrid g = grid_for(f, 40);
    f.fill_grid(g);
    ASSERT_EQ(g.values.size(), size_t(g.dims.x) * g.dims.y * g.dims.z);
    expect_grid_matches_value(f, g);
  }
  // A grid covering only part of the generators, flat in z, and one with a single plane.
  DensityField f(gens, 0.15f, 0.4f);
  ScalarGrid part;
  part.dims = {33, 17, 5};
  part.origin = {10.3f, -4.9f, 2.4f};
  part.spacing = 0.02f;
  f.fill_grid(part);
  expect_grid_matches_value(f, part);
  ScalarGrid one;
  one.dims = {20, 20, 1};
  one.origin = {10.0f, -5.0f, 2.5f};
  one.spacing = 0.05f;
  f.fill_grid(one);
  expect_grid_matches_value(f, one);
}

TEST(Density, FillGridFarFromTheOrigin) {
  // Float node positions near 1e5 are 1/128 apart, coarser than the spacing (1/256): nodes
  // pile up, and each still gets exactly value() at its (rounded) position.
  const std::vector<glm::vec3> gens = random_points(300, 41, 0.2f, glm::vec3(1e5f));
  DensityField f(gens, 0.03f, 0.5f);
  ScalarGrid g;
  g.dims = {60, 60, 60};
  g.origin = glm::vec3(1e5f) - glm::vec3(0.02f);
  g.spacing = 1.0f / 256.0f;
  f.fill_grid(g);
  expect_grid_matches_value(f, g);
  EXPECT_GT(*std::max_element(g.values.begin(), g.values.end()), 0.0f);
}

TEST(Density, FillGridOnASampleTree) {
  PlantOptions o;
  o.leaves = 3000;
  Scene s = make_plant(o);
  std::vector<glm::vec3> gens = make_generators(s, {});
  const Bounds b = s.bounds(Role::Foliage);
  DensityField f(std::move(gens), 0.05f * b.diagonal(), 0.5f);
  ScalarGrid g = grid_for(f, 48);
  f.fill_grid(g);
  expect_grid_matches_value(f, g);
  // Inside somewhere, outside at the grid's corner.
  EXPECT_GT(*std::max_element(g.values.begin(), g.values.end()), 0.0f);
  EXPECT_FLOAT_EQ(g.at(0, 0, 0), -0.5f);
}

TEST(Density, Deterministic) {
  const std::vector<glm::vec3> gens = random_points(20000, 5);
  DensityField f(gens, 0.08f, 0.3f);
  ScalarGrid a = grid_for(f, 64), b = a, c = a;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  f.fill_grid(a);
  omp_set_num_threads(2);
  f.fill_grid(b);
  omp_set_num_threads(3);
  f.fill_grid(c);
  omp_set_num_threads(threads);
  ASSERT_EQ(a.values.size(), b.values.size());
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(a.values.data(), c.values.data(), a.values.size() * sizeof(float)), 0);
  ScalarGrid again = grid_for(f, 64);
  f.fill_grid(again);
  EXPECT_EQ(again.values, a.values);
  // Building the field again gives the same values.
  DensityField f2(gens, 0.08f, 0.3f);
  for (size_t i = 0; i < gens.size(); i += 501)
    EXPECT_EQ(f2.value(gens[i]), f.value(gens[i]));
}

TEST(Density, InvalidParametersThrow) {
  const std::vector<glm::vec3> gens = {glm::vec3(0.0f)};
  for (float rho : {0.0f, -1.0f, -0.0f, float(NAN), float(INFINITY), -float(INFINITY)}) {
    try {
      DensityField f(gens, rho, 0.5f);
      ADD_FAILURE() << "rho " << rho << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "rho");
    }
  }
  for (float tau : {-0.1f, -1e-30f, float(NAN), float(INFINITY)}) {
    try {
      DensityField f(gens, 1.0f, tau);
      ADD_FAILURE() << "tau " << tau << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "tau");
    }
  }
  EXPECT_NO_THROW(DensityField(gens, 1e-30f, 0.0f));
  EXPECT_NO_THROW(DensityField(gens, 1e30f, 100.0f));
  EXPECT_THROW(DensityField({glm::vec3(0.0f), glm::vec3(NAN, 0, 0)}, 1.0f, 0.5f), InputError);
  EXPECT_THROW(DensityField({glm::vec3(0.0f, INFINITY, 0)}, 1.0f, 0.5f), InputError);
}

TEST(Density, TinyRhoGivesIsolatedSpikes) {
  const std::vector<glm::vec3> gens = random_points(5000, 13, 10.0f);
  const float tau = 0.5f;
  for (float rel : {1e-6f, 1e-12f}) {
    const float rho = rel * 10.0f;
    DensityField f(gens, rho, tau);
    for (size_t i = 0; i < gens.size(); i += 7) {
      EXPECT_FLOAT_EQ(f.value(gens[i]), 1.0f - tau);
      glm::vec3 g;
      EXPECT_FLOAT_EQ(f.value_and_gradient(gens[i] + glm::vec3(0.5f * rho, 0, 0), g),
                      brute_force(gens, rho, tau, gens[i] + glm::vec3(0.5f * rho, 0, 0)));
      EXPECT_TRUE(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z));
      EXPECT_FLOAT_EQ(f.value(gens[i] + glm::vec3(0, 2.0f * rho + 1e-5f, 0)), -tau);
    }
    ScalarGrid g = grid_for(f, 32);
    f.fill_grid(g);
    for (float v : g.values)
      ASSERT_TRUE(std::isfinite(v));
    expect_grid_matches_value(f, g);
  }
}

TEST(Density, HugeRhoCoversEverything) {
  const std::vector<glm::vec3> gens = random_points(200, 17, 1.0f);
  const float rho = 1e4f, tau = 0.5f;
  DensityField f(gens, rho, tau);
  // s <= 3 / 1e8 for every pair in the unit box: F ~ N (1 - tiny) - tau.
  const double n = double(gens.size());
  for (glm::vec3 q : {glm::vec3(0.0f), glm::vec3(0.5f), glm::vec3(1.0f), gens[3]}) {
    const float v = f.value(q);
    EXPECT_LE(v, n - tau);
    EXPECT_GE(v, n * (1.0 - 1e-7) - tau);
  }
  ScalarGrid g = make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 16);
  f.fill_grid(g);
  for (float v : g.values) {
    ASSERT_LE(v, n - tau);
    ASSERT_GE(v, n * (1.0 - 1e-7) - tau);
  }
  expect_grid_matches_value(f, g);
  EXPECT_TRUE(std::isfinite(DensityField(gens, 1e30f, 0.0f).value(glm::vec3(0.5f))));
}

TEST(Density, SingleGenerator) {
  const glm::vec3 p(0.3f, 0.7f, -0.2f);
  const float rho = 0.4f, tau = 0.1f;
  DensityField f({p}, rho, tau);
  const Bounds b = f.generator_bounds();
  EXPECT_EQ(b.min, p);
  EXPECT_EQ(b.max, p);
  ScalarGrid g = grid_for(f, 20);
  f.fill_grid(g);
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x)
        expect_close(g.at(x, y, z), brute_force({p}, rho, tau, g.position(x, y, z)), tau, 1e-6,
                     "single generator node");
}

TEST(Density, CoincidentGenerators) {
  const glm::vec3 p(1.0f, 2.0f, 3.0f);
  const int k = 7;
  const float rho = 0.5f, tau = 0.3f;
  DensityField f(std::vector<glm::vec3>(k, p), rho, tau);
  DensityField one({p}, rho, tau);
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> u(-0.6f, 0.6f);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 q = p + glm::vec3(u(rng), u(rng), u(rng));
    const double s = glm::dot(glm::dvec3(q - p), glm::dvec3(q - p)) / (rho * rho);
    const double expected = s < 1.0 ? k * (1.0 - s) * (1.0 - s) - tau : -tau;  // k (1 - s)^2 - tau
    EXPECT_NEAR(f.value(q), expected, 1e-5);
    glm::vec3 gk, g1;
    f.value_and_gradient(q, gk);
    one.value_and_gradient(q, g1);
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(gk[a], k * g1[a], 1e-4f * std::max(1.0f, std::abs(gk[a])));
  }
  ScalarGrid g = grid_for(f, 16);
  f.fill_grid(g);
  expect_grid_matches_value(f, g);
}

TEST(Density, ScaledScenesGiveTheSameField) {
  const std::vector<glm::vec3> gens = random_points(1500, 23, 1.0f, glm::vec3(2.0f, 0.0f, -1.0f));
  const float rho = 0.12f, tau = 0.4f;
  DensityField base(gens, rho, tau);
  ScalarGrid gb = grid_for(base, 32);
  base.fill_grid(gb);
  for (float k : {1e-4f, 1e4f}) {
    std::vector<glm::vec3> scaled = gens;
    for (glm::vec3& p : scaled)
      p *= k;
    DensityField f(scaled, rho * k, tau);
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> u(-0.2f, 1.2f);
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 q = glm::vec3(2.0f, 0.0f, -1.0f) + glm::vec3(u(rng), u(rng), u(rng));
      expect_close(f.value(q * k), base.value(q), tau, 1e-4, "scaled query");
      glm::vec3 gs, g1;
      f.value_and_gradient(q * k, gs);
      base.value_and_gradient(q, g1);
      for (int a = 0; a < 3; ++a)  // the gradient scales by 1 / k
        EXPECT_NEAR(gs[a] * k, g1[a], 1e-3f * std::max(1.0f, glm::length(g1)));
    }
    ScalarGrid gs = grid_for(f, 32);
    ASSERT_EQ(gs.dims, gb.dims);
    f.fill_grid(gs);
    for (size_t i = 0; i < gs.values.size(); ++i)
      ASSERT_NEAR(gs.values[i], gb.values[i], 1e-4f * std::max(1.0f, std::abs(gb.values[i]) + tau))
          << "scale " << k << " node " << i;
  }
}

TEST(Density, NoGeneratorsAndFarQueries) {
  DensityField empty({}, 1.0f, 0.25f);
  EXPECT_TRUE(empty.generator_bounds().empty());
  EXPECT_FLOAT_EQ(empty.value(glm::vec3(0.0f)), -0.25f);
  ScalarGrid g = make_grid(glm::vec3(0.0f), glm::vec3(1.0f), 4);
  empty.fill_grid(g);
  for (float v : g.values)
    EXPECT_FLOAT_EQ(v, -0.25f);

  DensityField f(random_points(100, 31), 0.2f, 0.25f);
  for (glm::vec3 q : {glm::vec3(1e30f), glm::vec3(-1e30f), glm::vec3(INFINITY, 0, 0),
                      glm::vec3(NAN), glm::vec3(0.5f, NAN, 0.5f)}) {
    glm::vec3 grad(1.0f);
    EXPECT_FLOAT_EQ(f.value(q), -0.25f);
    EXPECT_FLOAT_EQ(f.value_and_gradient(q, grad), -0.25f);
    EXPECT_EQ(grad, glm::vec3(0.0f));
  }
  // A grid far from every generator.
  ScalarGrid far = make_grid(glm::vec3(100.0f), glm::vec3(101.0f), 4);
  f.fill_grid(far);
  for (float v : far.values)
    EXPECT_FLOAT_EQ(v, -0.25f);
}

TEST(Density, MoveKeepsTheField) {
  const std::vector<glm::vec3> gens = random_points(500, 37);
  DensityField a(gens, 0.1f, 0.2f);
  const float v = a.value(gens[0]);
  DensityField b(std::move(a));
  EXPECT_FLOAT_EQ(b.value(gens[0]), v);
  DensityField c({}, 1.0f, 0.0f);
  c = std::move(b);
  EXPECT_FLOAT_EQ(c.value(gens[0]), v);
  EXPECT_EQ(c.generators().size(), gens.size());
}

}  // namespace
}  // namespace sylva
