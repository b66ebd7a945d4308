// Benchmarks for the styles (issue "Styles"): one frame of each built-in preset at 1024² on
// the 100k-leaf sample tree, through the render graph as `sylva render` builds it (raster
// pass + the style's image passes), against the bare raster pass (colour only) of the same
// scene. The Luft preprocessing is scene-level and cached (npr/foliage_cache.h), so it is
// computed once outside the timed loop. Reports medians (run with --benchmark_repetitions);
// the cost ratios to the bare raster pass are worked out from them.
#include <benchmark/benchmark.h>

#include <memory>

#include "core/gl/raster_pass.h"
#include "npr/foliage_illumination.h"
#include "npr/leaf_clusters.h"
#include "styles/style.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

constexpr int kLeaves = 100'000;
constexpr int kSize = 1024;

struct Rig {
  Scene scene;
  std::unique_ptr<GlContext> context = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  std::shared_ptr<const VertexShading> shading;
  Camera camera;
  Rig() {
    scene = perf::sample_tree(kLeaves);
    assign_clusters(scene, ClusterOptions{});
    raster = std::make_unique<Rasterizer>(*context);
    raster->upload(scene);
    shading = std::make_shared<const VertexShading>(vertex_shading(
        compute_foliage_illumination(scene, FoliageParams{}), KaEncoding::Attribute));
    camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, kSize, kSize);
  }
};

Rig& rig() {
  static Rig r;
  return r;
}

const char* const kStyles[] = {"raster", "standard", "expressive", "ink", "toon", "watercolor"};

void BM_Style(benchmark::State& state) {
  Rig& r = rig();
  const std::string name = kStyles[state.range(0)];
  state.SetLabel(name);
  const std::unique_ptr<Style> style =
      std::make_unique<Style>(name == "raster" ? "standard" : name);
  for (auto _ : state) {
    RenderGraph graph;
    RasterSetup setup;
    setup.rasterizer = r.raster.get();
    setup.camera = r.camera;
    setup.lighting = Lighting::three_point();
    style->configure(setup.request);
    if (style->normals() != NormalMode::Original) {
      const int shading = graph.resource("vertex-shading");
      graph.add_pass("cached-shading", {}, {shading},
                     [&r, shading](PassContext& ctx) { ctx.write(shading, r.shading); });
      setup.shading = shading;
      setup.request.scaled_normals = style->normals() == NormalMode::RealignedScaled;
    }
    const GBufferHandles gb = add_raster_pass(graph, setup);
    StyleContext context;
    context.lighting = setup.lighting;
    context.view = setup.camera.view;
    context.background = setup.request.background;
    context.foliage_diagonal = r.scene.bounds(Role::Foliage).diagonal();
    const int out = name == "raster" ? gb.color : style->build(graph, gb, context);
    graph.present(out);
    graph.execute();
    benchmark::DoNotOptimize(graph.get<cv::Mat>(out).data);
  }
}
BENCHMARK(BM_Style)
    ->DenseRange(0, 5)
    ->ArgName("style")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
