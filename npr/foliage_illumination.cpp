#include "npr/foliage_illumination.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.h"
#include "core/scene/instances.h"
#include "core/scene/load.h"
#include "npr/density_field.h"
#include "npr/generators.h"
#include "npr/realign.h"

namespace sylva {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// 2^28 kernel evaluations for fraction = auto: ~0.1 s of splatting on 2 cores; a 100k-leaf tree
// at grid 128 keeps ~30% of its leaves (4 deg mean normal error against all of them, per
// `sylva tradeoff`) where 2^26 kept 8% (8 deg).
constexpr double kSplatBudget = 268435456.0;

// The q-quantile (q in [0, 1]) of v, v not empty; reorders v.
float quantile(std::vector<float>& v, double q) {
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

size_t count_leaves(const Scene& scene) {
  std::vector<char> seen(size_t(scene.max_primitive_id()) + 1, 0);
  size_t n = 0;
  for (const Mesh& m : scene.meshes)
    for (size_t t = 0; t < m.triangle_count(); ++t)
      if (m.roles[t] == Role::Foliage && !seen[m.primitive_ids[t]])
        seen[m.primitive_ids[t]] = 1, ++n;
  return n;
}

// Per vertex: does any foliage triangle use it.
std::vector<char> foliage_vertices(const Mesh& m) {
  std::vector<char> f(m.positions.size(), 0);
  for (size_t t = 0; t < m.triangle_count(); ++t)
    if (m.roles[t] == Role::Foliage)
      for (int k = 0; k < 3; ++k)
        f[m.indices[3 * t + k]] = 1;
  return f;
}

bool inside_box(const ScalarGrid& g, const glm::vec3& p) {
  const glm::vec3 hi = g.position(g.dims.x - 1, g.dims.y - 1, g.dims.z - 1);
  return p.x >= g.origin.x && p.y >= g.origin.y && p.z >= g.origin.z && p.x <= hi.x &&
         p.y <= hi.y && p.z <= hi.z;
}

// F at p: the grid's trilinear value inside its box; outside, no generator is within rho
// (the box is the foliage bounds padded by rho), so F = -tau exactly.
float density_at(const ScalarGrid& g, float tau, const glm::vec3& p) {
  return inside_box(g, p) ? g.sample(p) : -tau;
}

glm::vec3 unit_or(const glm::vec3& v, const glm::vec3& fallback) {
  const float len = glm::length(v);
  return len > 1e-20f && std::isfinite(len) ? v / len : fallback;
}

void check_scene(const Scene& scene) {
  for (const Mesh& m : scene.meshes)
    SYLVA_CHECK(
        m.roles.size() == m.triangle_count() && m.primitive_ids.size() == m.triangle_count(),
        "foliage illumination needs roles and primitive ids (finish_scene)");
  if (scene.bounds(Role::Foliage).empty())
    throw InputError("scene",
                     "has no foliage to build the implicit surface from (see "
                     "--foliage and `sylva info`)");
}

// rho: auto from the model's size and leaf spacing (Luft §3.1: "values that provide adequate
// results can be automatically specified with regard to the size of the model"). Sets
// st.leaves and st.rho.
void choose_rho(const Scene& scene, const Bounds& fb, const FoliageParams& p, FoliageStats& st) {
  st.leaves = count_leaves(scene);
  const double diag = std::max<double>(fb.diagonal(), 1e-30);
  const glm::dvec3 ext = glm::max(glm::dvec3(fb.max - fb.min), glm::dvec3(0.01 * diag));
  const double spacing = std::cbrt(ext.x * ext.y * ext.z / double(std::max<size_t>(st.leaves, 1)));
  const double automatic = p.picture_rho > 0.0 ? p.picture_rho : 0.08 * diag;
  st.rho = p.rho.resolve(diag, std::max(automatic, 3.0 * spacing));
  if (!(st.rho > 0.0) || !std::isfinite(st.rho)) throw InputError("rho", "must be > 0");
}

// The generator points (§3.1), their fraction auto within the splatting budget. Sets
// st.fraction and st.generators.
std::vector<glm::vec3> choose_generators(const Scene& scene, const ScalarGrid& grid,
                                         const FoliageParams& p, FoliageStats& st) {
  const double ball = 4.0 / 3.0 * std::numbers::pi * std::pow(st.rho / grid.spacing, 3.0);
  st.fraction =
      p.fraction ? *p.fraction
                 : std::clamp(kSplatBudget / (double(st.leaves) * std::max(ball, 1.0)), 1e-6, 1.0);
  GeneratorOptions go;
  go.fraction = st.fraction;
  go.per_triangle = p.per_triangle;
  go.seed = p.seed;
  std::vector<glm::vec3> generators = make_generators(scene, go);
  st.generators = generators.size();
  return generators;
}

// tau: auto = half the 10th percentile of the raw density at (up to 4096 strided) generators:
// the surface wraps nearly every leaf with a margin the grid can resolve.
double choose_tau(const std::vector<glm::vec3>& generators, float rho, const FoliageParams& p) {
  if (p.tau) return *p.tau;
  const DensityField raw(generators, rho, 0.0f);
  const size_t stride = std::max<size_t>(1, generators.size() / 4096);
  std::vector<float> at;
  for (size_t i = 0; i < generators.size(); i += stride)
    at.push_back(raw.value(generators[i]));
  return 0.5 * quantile(at, 0.10);
}

// The grid holds no positive value: says whether the grid is too coarse or tau too high.
[[noreturn]] void explain_empty_field(const DensityField& field, const ScalarGrid& grid,
                                      const FoliageParams& p, const FoliageStats& st) {
  const auto [lo, hi] = std::minmax_element(grid.values.begin(), grid.values.end());
  char buf[256];
  float peak = -float(st.tau);  // is the surface there but between the grid's nodes?
  for (size_t i = 0; i < field.generators().size(); i += std::max<size_t>(1, st.generators / 4096))
    peak = std::max(peak, field.value(field.generators()[i]));
  if (peak > 0.0f) {
    std::snprintf(buf, sizeof buf,
                  "%d cells are too coarse for rho %g: no grid node lies inside the surface; "
                  "raise grid or rho",
                  p.grid, st.rho);
    throw InputError("grid", buf);
  }
  std::snprintf(buf, sizeof buf,
                "tau %g is at or above every density: F + tau spans [%g, %g] with rho %g; "
                "lower tau or raise rho",
                st.tau, double(*lo) + st.tau, double(*hi) + st.tau, st.rho);
  throw InputError("tau", buf);
}

// The implicit surface with outward normals -grad F / |grad F| (analytic gradient).
SurfaceMesh build_surface(const DensityField& field, const ScalarGrid& grid,
                          const FoliageParams& p) {
  SurfaceMesh surface = extract_isosurface(grid);
  optimize_surface(surface, p.optimize);
  surface.normals.resize(surface.positions.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(surface.positions.size()); ++i) {
    glm::vec3 g;
    field.value_and_gradient(surface.positions[size_t(i)], g);
    surface.normals[size_t(i)] = unit_or(
        -g, unit_or(-grid.sample_gradient(surface.positions[size_t(i)]), glm::vec3(0, 1, 0)));
  }
  if (surface.positions.empty())
    throw InputError("grid",
                     "the implicit surface has no vertices at this grid resolution; "
                     "raise grid or rho");
  return surface;
}

// Per mesh and vertex: the density F + tau; sets st.density_min/max. `foliage_density` gets
// the foliage vertices' values.
std::vector<std::vector<float>> vertex_densities(const Scene& scene, const ScalarGrid& grid,
                                                 FoliageStats& st,
                                                 std::vector<float>& foliage_density) {
  std::vector<std::vector<float>> density(scene.meshes.size());
  st.density_min = 1e30;
  st.density_max = -1e30;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& m = scene.meshes[mi];
    std::vector<float>& d = density[mi];
    d.resize(m.positions.size());
#pragma omp parallel for schedule(static)
    for (long v = 0; v < long(d.size()); ++v)
      d[size_t(v)] = density_at(grid, float(st.tau), m.positions[size_t(v)]);
    const std::vector<char> fol = foliage_vertices(m);
    for (size_t v = 0; v < d.size(); ++v) {
      st.density_min = std::min(st.density_min, double(d[v]));
      st.density_max = std::max(st.density_max, double(d[v]));
      if (fol[v]) foliage_density.push_back(d[v]);
    }
  }
  return density;
}

// Foliage vertices of all meshes, gathered for one nearest-surface query (scenes with a mesh
// per leaf would otherwise build a kd-tree per leaf).
struct FoliagePoints {
  std::vector<glm::vec3> points;
  std::vector<std::pair<uint32_t, uint32_t>> which;  // (mesh, vertex)
};

// Each vertex's own unit normal and its ka (Eq. 4) into `out`; returns the foliage vertices.
FoliagePoints own_normals_and_ka(const Scene& scene, const std::vector<std::vector<float>>& density,
                                 const AmbientParams& ap, FoliageIllumination& out) {
  FoliagePoints f;
  out.normals.resize(scene.meshes.size());
  out.ka.resize(scene.meshes.size());
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& mesh = scene.meshes[mi];
    Mesh m = mesh.normals.empty() ? mesh : Mesh{};
    if (!m.positions.empty()) compute_vertex_normals(m);
    const std::vector<glm::vec3>& own = mesh.normals.empty() ? m.normals : mesh.normals;
    std::vector<glm::vec3>& n = out.normals[mi];
    std::vector<float>& ka = out.ka[mi];
    n.resize(mesh.positions.size());
    ka.resize(mesh.positions.size());
    for (size_t v = 0; v < n.size(); ++v) {
      n[v] = unit_or(own[v], glm::vec3(0, 0, 1));
      ka[v] = ambient_transfer(density[mi][v], ap);
    }
    const std::vector<char> fol = foliage_vertices(mesh);
    for (size_t v = 0; v < fol.size(); ++v)
      if (fol[v]) f.points.push_back(mesh.positions[v]), f.which.emplace_back(mi, v);
  }
  return f;
}

// The foliage normals realigned (§3.3) toward the surface's nearest normal or the field's
// gradient.
void realign_normals(const FoliagePoints& f, const ScalarGrid& grid, const FoliageParams& p,
                     FoliageIllumination& out) {
  std::vector<glm::vec3> target(f.points.size());
  if (p.normals == NormalSource::Surface) {
    if (!f.points.empty()) target = nearest_surface_normals(out.surface, f.points);
  } else {
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(f.points.size()); ++i) {
      const auto [mi, v] = f.which[size_t(i)];
      target[size_t(i)] = unit_or(-grid.sample_gradient(f.points[size_t(i)]), out.normals[mi][v]);
    }
  }
  for (size_t i = 0; i < f.points.size(); ++i) {
    glm::vec3& n = out.normals[f.which[i].first][f.which[i].second];
    n = blend_normal(n, target[i], p.blend);
  }
}

}  // namespace

void validate_foliage_params(const FoliageParams& p) {
  if (p.tau && !(std::isfinite(*p.tau) && *p.tau >= 0.0f))
    throw InputError("tau", "must be 'auto' or a finite density >= 0");
  if (p.fraction && !(*p.fraction > 0.0 && *p.fraction <= 1.0))
    throw InputError("fraction", "must be 'auto' or in (0, 1]");
  if (p.grid < 2 || p.grid > 1024)
    throw InputError("grid", "must be in [2, 1024] cells, got " + std::to_string(p.grid));
  if (!(p.blend >= 0.0f && p.blend <= 1.0f)) throw InputError("blend", "must be in [0, 1]");
  validate_ambient(p.ambient);
}

namespace {

// A plant without foliage: its own unit normals, ka 1 (Eq. 4 at density 0).
FoliageIllumination unshaded(const Scene& plant) {
  FoliageIllumination out;
  for (const Mesh& mesh : plant.meshes) {
    Mesh m = mesh.normals.empty() ? mesh : Mesh{};
    if (!m.positions.empty()) compute_vertex_normals(m);
    const std::vector<glm::vec3>& own = mesh.normals.empty() ? m.normals : mesh.normals;
    std::vector<glm::vec3> n(own.size());
    for (size_t v = 0; v < n.size(); ++v)
      n[v] = unit_or(own[v], glm::vec3(0, 0, 1));
    out.normals.push_back(std::move(n));
    out.ka.emplace_back(mesh.positions.size(), 1.0f);
  }
  return out;
}

// The first plant with foliage gives rho, tau, fraction, d_min and F; counts and timings add.
void merge_stats(FoliageStats& st, const FoliageStats& r, bool first) {
  if (first) {
    std::vector<FoliageStats> plants = std::move(st.plants);
    st = r;
    st.plant.clear();
    st.plants = std::move(plants);
    return;
  }
  st.leaves += r.leaves;
  st.generators += r.generators;
  st.surface_triangles += r.surface_triangles;
  st.seconds_field += r.seconds_field;
  st.seconds_surface += r.seconds_surface;
  st.seconds_shading += r.seconds_shading;
  st.from_cache = st.from_cache && r.from_cache;
}

// Plant p's result into the scene's per-mesh arrays and the merged stats.
void merge_plant(const Scene& scene, size_t p, FoliageIllumination&& r, bool shaded, bool first,
                 FoliageIllumination& out) {
  const std::vector<uint32_t>& meshes = scene.plants[p].meshes;
  for (size_t k = 0; k < meshes.size(); ++k) {
    out.normals[meshes[k]] = std::move(r.normals[k]);
    out.ka[meshes[k]] = std::move(r.ka[k]);
  }
  out.plant_surfaces.push_back(std::move(r.surface));
  r.stats.plant = scene.plants[p].name;
  if (shaded) merge_stats(out.stats, r.stats, first);
  out.stats.plants.push_back(std::move(r.stats));
}

}  // namespace

FoliageIllumination foliage_per_plant(const Scene& scene,
                                      const std::function<FoliageIllumination(const Scene&)>& one) {
  if (!scene.instanced()) return one(scene);
  FoliageIllumination out;
  out.normals.resize(scene.meshes.size());
  out.ka.resize(scene.meshes.size());
  bool any = false;
  for (size_t p = 0; p < scene.plants.size(); ++p) {
    const Scene plant = plant_scene(scene, p, false);
    const bool shaded = !plant.bounds(Role::Foliage).empty();
    merge_plant(scene, p, shaded ? one(plant) : unshaded(plant), shaded, shaded && !any, out);
    any = any || shaded;
  }
  if (!any) check_scene(scene);  // throws: no foliage anywhere
  return out;
}

FoliageIllumination compute_foliage_illumination(const Scene& scene, const FoliageParams& p) {
  validate_foliage_params(p);
  if (scene.instanced())
    return foliage_per_plant(
        scene, [&p](const Scene& plant) { return compute_foliage_illumination(plant, p); });
  check_scene(scene);
  const Bounds fb = scene.bounds(Role::Foliage);
  FoliageIllumination out;
  FoliageStats& st = out.stats;
  auto t0 = Clock::now();
  choose_rho(scene, fb, p, st);
  const float rho = float(st.rho);
  ScalarGrid grid = make_grid(fb.min - glm::vec3(rho), fb.max + glm::vec3(rho), p.grid);
  std::vector<glm::vec3> generators = choose_generators(scene, grid, p, st);
  st.tau = choose_tau(generators, rho, p);
  const DensityField field(std::move(generators), rho, float(st.tau));
  field.fill_grid(grid);
  if (!(*std::max_element(grid.values.begin(), grid.values.end()) > 0.0f))
    explain_empty_field(field, grid, p, st);
  st.seconds_field = since(t0);

  t0 = Clock::now();
  if (p.normals == NormalSource::Surface) {
    out.surface = build_surface(field, grid, p);
    st.surface_triangles = out.surface.triangle_count();
  }
  st.seconds_surface = since(t0);

  t0 = Clock::now();
  std::vector<float> foliage_density;
  const std::vector<std::vector<float>> density =
      vertex_densities(scene, grid, st, foliage_density);
  AmbientParams ap = p.ambient;
  if (p.d_min_auto) {
    const float q = foliage_density.empty() ? 0.0f : quantile(foliage_density, 0.90);
    ap.d_min = q > 0.0f ? q : std::max(float(st.density_max), 1e-6f);
  }
  st.d_min = ap.d_min;
  const FoliagePoints foliage = own_normals_and_ka(scene, density, ap, out);
  realign_normals(foliage, grid, p, out);
  st.seconds_shading = since(t0);
  return out;
}

VertexShading vertex_shading(const FoliageIllumination& r, KaEncoding encoding) {
  VertexShading s;
  s.normals = r.normals;
  s.oriented_foliage = true;
  if (encoding == KaEncoding::Attribute) {
    s.ka = r.ka;
    return s;
  }
  for (size_t m = 0; m < s.normals.size(); ++m)
    for (size_t v = 0; v < s.normals[m].size(); ++v)
      s.normals[m][v] = encode_ka(s.normals[m][v], r.ka[m][v]);
  return s;
}

std::string describe(const FoliageStats& s) {
  if (!s.plants.empty()) {
    std::string out = std::to_string(s.plants.size()) + " plants";
    for (const FoliageStats& p : s.plants)
      out += "; " + p.plant + ": " + describe(p);
    return out;
  }
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%zu leaves, %zu generators (fraction %.3g), rho %.4g, tau %.4g, d_min %.4g, "
                "F in [%.3g, %.3g], surface %zu triangles; %.2f s field, %.2f s surface, "
                "%.2f s shading%s",
                s.leaves, s.generators, s.fraction, s.rho, s.tau, s.d_min, s.density_min,
                s.density_max, s.surface_triangles, s.seconds_field, s.seconds_surface,
                s.seconds_shading, s.from_cache ? " (read from the cache)" : "");
  return buf;
}

}  // namespace sylva
