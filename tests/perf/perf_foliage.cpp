// Benchmarks for the whole Luft preprocessing (npr/foliage_illumination.h): sample trees of
// 10k to 1M leaves at grid 128, with the default automatic parameters (fraction = auto: a
// splat budget) and with every leaf a generator (fraction 1); and reading a cached result.
// Counters give the stage times of the last iteration. Reports medians (run with
// --benchmark_repetitions); the log-log slope of time against leaves is worked out from them.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>

#include "npr/foliage_cache.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

void report(benchmark::State& state, const FoliageStats& st) {
  state.counters["generators"] = double(st.generators);
  state.counters["fraction"] = st.fraction;
  state.counters["field_s"] = st.seconds_field;
  state.counters["surface_s"] = st.seconds_surface;
  state.counters["shading_s"] = st.seconds_shading;
  state.counters["surface_tris"] = double(st.surface_triangles);
}

// range(0) leaves, range(1) 0 = fraction auto, 1 = every leaf a generator.
void BM_Preprocess(benchmark::State& state) {
  const Scene& s = perf::sample_tree(int(state.range(0)));
  FoliageParams p;
  p.grid = 128;
  if (state.range(1) == 1) p.fraction = 1.0;
  FoliageStats st;
  for (auto _ : state) {
    FoliageIllumination r = compute_foliage_illumination(s, p);
    st = r.stats;
    benchmark::DoNotOptimize(r.ka.data());
  }
  report(state, st);
}
BENCHMARK(BM_Preprocess)
    ->ArgsProduct({{10'000, 30'000, 100'000, 300'000, 1'000'000}, {0}})
    ->ArgsProduct({{10'000, 30'000, 100'000, 300'000}, {1}})
    ->ArgNames({"leaves", "all_generators"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A second render of the same scene: key hashing plus reading and checking the entry.
void BM_CacheHit(benchmark::State& state) {
  const Scene& s = perf::sample_tree(int(state.range(0)));
  const std::string dir =
      (std::filesystem::temp_directory_path() / "sylva-perf-foliage-cache").string();
  const ResultCache cache(dir);
  FoliageParams p;
  p.grid = 128;
  cached_foliage_illumination(s, p, &cache);  // fill
  for (auto _ : state) {
    FoliageCacheUse use;
    FoliageIllumination r = cached_foliage_illumination(s, p, &cache, &use);
    if (!use.hit) state.SkipWithError("cache miss");
    benchmark::DoNotOptimize(r.ka.data());
  }
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_CacheHit)
    ->Arg(100'000)
    ->ArgName("leaves")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
