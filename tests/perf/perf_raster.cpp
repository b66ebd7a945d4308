// Benchmarks for the foundation: the raster pass alone on sample trees of 10k, 100k and 1M
// leaves at 512² and 1024² with 1 target (colour), 5 (colour, normal, depth, id, ka) and every
// target (argument 6: the full G-buffer, adding position and albedo), and
// loading a written .glb. Reports medians (run with --benchmark_repetitions) and the
// process's peak RSS so far as a counter.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <filesystem>
#include <map>
#include <memory>

#include "core/gl/rasterizer.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "npr/leaf_clusters.h"
#include "samples/plants.h"

namespace sylva {
namespace {

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

const Scene& tree(int leaves) {
  static std::map<int, Scene> cache;
  auto it = cache.find(leaves);
  if (it != cache.end()) return it->second;
  PlantOptions o;
  o.kind = PlantKind::Tree;
  o.leaves = leaves;
  Scene s = make_plant(o);
  assign_clusters(s, ClusterOptions{});
  return cache.emplace(leaves, std::move(s)).first->second;
}

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = create_gl_context();
  return *ctx;
}

void BM_RasterPass(benchmark::State& state) {
  int leaves = static_cast<int>(state.range(0));
  int size = static_cast<int>(state.range(1));
  const int64_t targets = state.range(2);
  const Scene& scene = tree(leaves);
  Rasterizer raster(context());
  raster.upload(scene);
  Camera cam = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, size, size);
  RasterRequest req;
  req.targets = targets == 6 ? kAllTargetsMask
                : targets == 5
                    ? (Target::Color | Target::Normal | Target::Depth | Target::Id | Target::Ka)
                    : static_cast<TargetMask>(Target::Color);
  Lighting light = Lighting::three_point();
  for (auto _ : state) {
    GBuffer g = raster.render(cam, light, req);
    benchmark::DoNotOptimize(g.color.data);
  }
  state.counters["triangles"] = static_cast<double>(scene.triangle_count());
  state.counters["peak_rss_mb"] = peak_rss_mb();
}
BENCHMARK(BM_RasterPass)
    ->ArgsProduct({{10'000, 100'000, 1'000'000}, {512, 1024}, {1, 5, 6}})
    ->ArgNames({"leaves", "size", "targets"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_LoadGlb(benchmark::State& state) {
  int leaves = static_cast<int>(state.range(0));
  std::string path =
      (std::filesystem::temp_directory_path() / ("sylva-perf-" + std::to_string(leaves) + ".glb"))
          .string();
  write_glb(tree(leaves), path);
  for (auto _ : state) {
    Scene s = load_scene(path);
    assign_clusters(s, ClusterOptions{});
    benchmark::DoNotOptimize(s.meshes.data());
  }
  std::filesystem::remove(path);
  state.counters["peak_rss_mb"] = peak_rss_mb();
}
BENCHMARK(BM_LoadGlb)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
