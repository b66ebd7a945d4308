// Benchmarks for ambient occlusion (issue "Ambient occlusion for crowns"): the raster pass at
// 1024² on the 100k-leaf sample tree with each AO model evaluated per fragment (BM_AoRaster:
// the colour pass alone, without and with Hegeman et al.'s sphere and k = 4 shells darkening
// its ambient term; then colour + the AO target read back, with none, constant, sphere,
// ellipsoid and k = 4 / 8 shells; shells and alpha*rho are fitted once, outside the loop, as
// a turntable does), and the ray-traced reference at 512² with 64 rays per pixel
// on 2 cores (BM_AoReference, reporting rays per second; BM_AoReferenceBuild: Embree's BVH
// over the scene, which make_scene_tracer pays once per scene). Targets: Hegeman adds
// <= 10 % to the raster pass; the reference takes <= 5 s. Reports medians (run with
// --benchmark_repetitions); the ratios are worked out from them.
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_inverse.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/gl/raster_pass.h"
#include "npr/ao_pass.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

constexpr int kLeaves = 100'000;
constexpr int kRasterSize = 1024;
constexpr int kReferenceSize = 512;
constexpr int kRays = 64;

struct Model {
  const char* label;
  const char* model;  // ao.model; nullptr = none
  int shells;
  bool ao_target;  // also read back the AO target (as `sylva buffers --buffers ao` does)
};
const Model kModels[] = {{"colour only", nullptr, 1, false},
                         {"hegeman-sphere, colour only", "hegeman-sphere", 1, false},
                         {"hegeman-shells k=4, colour only", "hegeman-shells", 4, false},
                         {"none + ao target", "none", 1, true},
                         {"constant + ao target", "constant", 1, true},
                         {"hegeman-sphere + ao target", "hegeman-sphere", 1, true},
                         {"hegeman-ellipsoid + ao target", "hegeman-ellipsoid", 1, true},
                         {"hegeman-shells k=4 + ao target", "hegeman-shells", 4, true},
                         {"hegeman-shells k=8 + ao target", "hegeman-shells", 8, true}};

struct Rig {
  const Scene& scene = perf::sample_tree(kLeaves);
  std::unique_ptr<GlContext> context = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  Rig() {
    raster = std::make_unique<Rasterizer>(*context);
    raster->upload(scene);
  }
  Camera camera(int size) const {
    return make_orbit_camera(scene.framing_sphere(), OrbitParams{}, size, size);
  }
};

Rig& rig() {
  static Rig r;
  return r;
}

void BM_AoRaster(benchmark::State& state) {
  Rig& r = rig();
  const Model& m = kModels[state.range(0)];
  state.SetLabel(m.label);
  RasterRequest request;
  if (m.model) {
    AoSettings settings;
    settings.model = parse_ao_model(m.model, "perf");
    settings.shells = m.shells;
    request.ao = scene_ao_shading(r.scene, settings, 1);  // fitted once, as per turntable
  }
  if (m.ao_target) request.targets = Target::Color | Target::Ao;
  const Camera camera = r.camera(kRasterSize);
  const Lighting lighting = Lighting::three_point();
  for (auto _ : state) {
    const GBuffer gb = r.raster->render(camera, lighting, request);
    benchmark::DoNotOptimize(gb.color.data);
  }
}
BENCHMARK(BM_AoRaster)
    ->DenseRange(0, int(std::size(kModels)) - 1)
    ->ArgName("model")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The covered pixels of a 512² frame as world-space points and normals, as the raytraced AO
// pass traces them.
struct ReferenceRig {
  AoReferenceScene tracer = make_scene_tracer(rig().scene);
  std::vector<glm::vec3> points, normals;
  ReferenceRig() {
    Rig& r = rig();
    const Camera camera = r.camera(kReferenceSize);
    RasterRequest request;
    request.targets = Target::Position | Target::Normal;
    const GBuffer gb = r.raster->render(camera, Lighting::three_point(), request);
    const glm::mat4 to_world = glm::inverse(camera.view);
    const glm::mat3 to_world_n = glm::inverseTranspose(glm::mat3(camera.view));
    for (int y = 0; y < gb.position.rows; ++y)
      for (int x = 0; x < gb.position.cols; ++x) {
        const cv::Vec3f p = gb.position.at<cv::Vec3f>(y, x);
        const cv::Vec3f n = gb.normal.at<cv::Vec3f>(y, x);
        if (n == cv::Vec3f(0, 0, 0)) continue;  // background
        points.push_back(glm::vec3(to_world * glm::vec4(p[0], p[1], p[2], 1.0f)));
        normals.push_back(glm::normalize(to_world_n * glm::vec3(n[0], n[1], n[2])));
      }
  }
};

ReferenceRig& reference_rig() {
  static ReferenceRig r;
  return r;
}

void BM_AoReference(benchmark::State& state) {
  ReferenceRig& r = reference_rig();
  AoReferenceOptions options;
  options.rays = kRays;
  for (auto _ : state) {
    const std::vector<float> v = r.tracer.visibility(r.points, r.normals, options);
    benchmark::DoNotOptimize(v.data());
  }
  state.counters["pixels"] = double(r.points.size());
  state.counters["rays_per_s"] = benchmark::Counter(
      double(r.points.size()) * kRays * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AoReference)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AoReferenceBuild(benchmark::State& state) {
  const Scene& scene = rig().scene;
  for (auto _ : state) {
    AoReferenceScene tracer = make_scene_tracer(scene);
    benchmark::DoNotOptimize(tracer.triangle_count());
  }
  state.counters["triangles"] = double(scene.triangle_count());
}
BENCHMARK(BM_AoReferenceBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
