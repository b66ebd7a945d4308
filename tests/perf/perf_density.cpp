// Benchmarks for the density field (Luft et al. §3.1): generator extraction, splatting the
// field into grids of 64, 128 and 256 cells, and exact value() at every foliage vertex, on
// sample trees of 10k, 100k and 1M leaves (value() at 10k and 100k) with rho = 5% of the foliage
// bounds diagonal and every leaf a generator. Reports medians (run with --benchmark_repetitions).
#include <benchmark/benchmark.h>

#include <map>

#include "npr/density_field.h"
#include "npr/generators.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

constexpr float kRhoShare = 0.05f;
constexpr float kTau = 0.5f;

const DensityField& field(int leaves) {
  static std::map<int, DensityField> cache;
  auto it = cache.find(leaves);
  if (it != cache.end()) return it->second;
  const Scene& s = perf::sample_tree(leaves);
  const float rho = kRhoShare * s.bounds(Role::Foliage).diagonal();
  return cache.emplace(leaves, DensityField(make_generators(s, {}), rho, kTau)).first->second;
}

void BM_Generators(benchmark::State& state) {
  const Scene& s = perf::sample_tree(int(state.range(0)));
  size_t n = 0;
  for (auto _ : state) {
    std::vector<glm::vec3> g = make_generators(s, {});
    n = g.size();
    benchmark::DoNotOptimize(g.data());
  }
  state.counters["generators"] = double(n);
}
BENCHMARK(BM_Generators)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->ArgName("leaves")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Building the hash grid over the generators.
void BM_BuildField(benchmark::State& state) {
  const Scene& s = perf::sample_tree(int(state.range(0)));
  const std::vector<glm::vec3> gens = make_generators(s, {});
  const float rho = kRhoShare * s.bounds(Role::Foliage).diagonal();
  for (auto _ : state) {
    DensityField f(gens, rho, kTau);
    benchmark::DoNotOptimize(&f);
  }
}
BENCHMARK(BM_BuildField)
    ->Arg(10'000)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->ArgName("leaves")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_FillGrid(benchmark::State& state) {
  const DensityField& f = field(int(state.range(0)));
  const Bounds b = f.generator_bounds();
  ScalarGrid grid =
      make_grid(b.min - glm::vec3(f.rho()), b.max + glm::vec3(f.rho()), int(state.range(1)));
  for (auto _ : state) {
    f.fill_grid(grid);
    benchmark::DoNotOptimize(grid.values.data());
  }
  state.counters["nodes"] = double(grid.values.size());
  state.counters["rho_cells"] = double(f.rho() / grid.spacing);
}
BENCHMARK(BM_FillGrid)
    ->ArgsProduct({{10'000, 100'000, 1'000'000}, {64, 128, 256}})
    ->ArgNames({"leaves", "grid"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Exact F at every foliage vertex, 2 threads (what per-vertex lookups cost without a grid).
// Not run at 1M leaves: each query there sums ~75k candidates (~10 min per iteration).
void BM_ValueAtVertices(benchmark::State& state) {
  const Scene& s = perf::sample_tree(int(state.range(0)));
  const DensityField& f = field(int(state.range(0)));
  std::vector<const glm::vec3*> vertices;
  for (const Mesh& m : s.meshes)
    if (!m.roles.empty() && m.roles[0] == Role::Foliage)
      for (const glm::vec3& p : m.positions)
        vertices.push_back(&p);
  std::vector<float> out(vertices.size());
  for (auto _ : state) {
#pragma omp parallel for schedule(dynamic, 1024)
    for (int64_t i = 0; i < int64_t(vertices.size()); ++i)
      out[size_t(i)] = f.value(*vertices[size_t(i)]);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["vertices"] = double(vertices.size());
  state.counters["queries_per_s"] =
      benchmark::Counter(double(vertices.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ValueAtVertices)
    ->Arg(10'000)
    ->Arg(100'000)
    ->ArgName("leaves")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
