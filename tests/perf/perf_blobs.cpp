// Benchmarks for blob painting (Dudley 2005; issue "Dudley blob paintings"): one frame of the
// `blobs` preset at 1024² on the 10k-leaf sample tree with 16 leaf clusters, split into the
// raster pass (colour, albedo, cluster ids, depth: BM_BlobRaster) and the whole frame
// (BM_BlobFrame: raster + leaf silhouettes + shrink-wrap + painting), and the blob passes alone
// on a fixed G-buffer (BM_BlobOutlines: the shrink-wrap of every cluster; BM_BlobPaint: the
// painting). Reports medians (run with --benchmark_repetitions). Dudley reports about 60 s a
// frame; the target is 0.5 s.
#include <benchmark/benchmark.h>

#include <memory>

#include "core/gl/raster_pass.h"
#include "npr/leaf_clusters.h"
#include "passes/blobs.h"
#include "passes/pass_common.h"
#include "styles/style.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

constexpr int kLeaves = 10'000;
constexpr int kClusters = 16;
constexpr int kSize = 1024;

struct Rig {
  Scene scene = perf::sample_tree(kLeaves);
  std::unique_ptr<GlContext> context = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  Camera camera;
  Style style{"blobs"};
  GBuffer gbuffer;  // the frame's buffers, for the pass-only benchmarks
  Rig() {
    ClusterOptions co;
    co.clusters = kClusters;
    assign_clusters(scene, co);
    raster = std::make_unique<Rasterizer>(*context);
    raster->upload(scene);
    camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, kSize, kSize);
    RasterRequest request;
    style.configure(request);
    request.targets = Target::Color | Target::Albedo | Target::Id | Target::Depth;
    gbuffer = raster->render(camera, Lighting::three_point(), request);
  }
  BlobFrame frame() const {
    BlobFrame f;
    f.lighting = Lighting::three_point();
    f.view = camera.view;
    f.branch_cluster = scene.branch_cluster_id();
    return f;
  }
};

Rig& rig() {
  static Rig r;
  return r;
}

// raster_only: present the raster pass's targets the style reads instead of its image.
void frame(Rig& r, bool raster_only) {
  RenderGraph graph;
  RasterSetup setup;
  setup.rasterizer = r.raster.get();
  setup.camera = r.camera;
  setup.lighting = Lighting::three_point();
  r.style.configure(setup.request);
  const GBufferHandles gb = add_raster_pass(graph, setup);
  StyleContext context;
  context.lighting = setup.lighting;
  context.view = setup.camera.view;
  context.background = setup.request.background;
  context.branch_cluster = r.scene.branch_cluster_id();
  ImageHandle out = gb.id;
  if (raster_only) {
    for (ImageHandle t : {gb.color, gb.albedo, gb.id, gb.depth})
      graph.present(t);
  } else {
    out = r.style.build(graph, gb, context).image;
    graph.present(out);
  }
  graph.execute();
  benchmark::DoNotOptimize(graph.get<cv::Mat>(out).data);
}

void BM_BlobRaster(benchmark::State& state) {
  Rig& r = rig();
  for (auto _ : state)
    frame(r, true);
}
BENCHMARK(BM_BlobRaster)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BlobFrame(benchmark::State& state) {
  Rig& r = rig();
  for (auto _ : state)
    frame(r, false);
}
BENCHMARK(BM_BlobFrame)->Unit(benchmark::kMillisecond)->UseRealTime();

ShrinkWrapParams wrap_params(const BlobParams& p) {
  ShrinkWrapParams sw;
  sw.control_points = p.control_points;
  sw.step = p.step;
  return sw;
}

void BM_BlobOutlines(benchmark::State& state) {
  Rig& r = rig();
  const BlobParams& p = r.style.params().blobs;
  const float radius = static_cast<float>(0.5 * p.gap * reference_scale(r.gbuffer.id.size()));
  size_t blobs = 0;
  for (auto _ : state) {
    const auto outlines = find_blob_outlines(r.gbuffer.id, r.gbuffer.depth,
                                             r.scene.branch_cluster_id(), wrap_params(p), radius);
    blobs = outlines.size();
    benchmark::DoNotOptimize(outlines.data());
  }
  state.counters["blobs"] = static_cast<double>(blobs);
}
BENCHMARK(BM_BlobOutlines)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BlobPaint(benchmark::State& state) {
  Rig& r = rig();
  const BlobParams& p = r.style.params().blobs;
  const float radius = static_cast<float>(0.5 * p.gap * reference_scale(r.gbuffer.id.size()));
  const auto outlines = find_blob_outlines(r.gbuffer.id, r.gbuffer.depth,
                                           r.scene.branch_cluster_id(), wrap_params(p), radius);
  const BlobSet set = still_blob_set(outlines);
  BlobImages in;
  in.color = r.gbuffer.color;
  in.albedo = r.gbuffer.albedo;
  in.id = r.gbuffer.id;
  for (auto _ : state) {
    const cv::Mat img = paint_blobs(in, set, r.frame(), p);
    benchmark::DoNotOptimize(img.data);
  }
}
BENCHMARK(BM_BlobPaint)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
