// Benchmark for the buffer files (issue "Buffers and renders for compositors and print"):
// writing every G-buffer of the 100k-leaf sample tree at 1024² (colour, normal, depth, position,
// id, ka, albedo; rendered once outside the timed loop) as `sylva buffers` writes them: the
// TIFF set (a file per buffer, 8-bit previews, camera.json), or one multi-channel EXR with
// ZIP, PIZ or no compression, and ZIP with the Cryptomatte layers of objects, materials and
// clusters. Reports medians (run with --benchmark_repetitions) and the bytes
// written as a counter; the EXR/TIFF time ratio is worked out from the medians.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "core/gl/rasterizer.h"
#include "core/io/buffer_files.h"
#include "npr/leaf_clusters.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;

struct Buffers {
  BufferImages images;
  std::vector<CryptomatteImage> mattes;  // object, material and cluster ids, one sample a pixel
  Camera camera;
  Buffers() {
    Scene scene = perf::sample_tree(100'000);
    assign_clusters(scene, ClusterOptions{});
    const std::unique_ptr<GlContext> context = create_gl_context();
    Rasterizer raster(*context);
    raster.upload(scene);
    camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, 1024, 1024);
    RasterRequest request;
    request.targets = kAllTargetsMask & ~static_cast<TargetMask>(Target::Ao);
    const GBuffer g = raster.render(camera, Lighting::three_point(), request);
    for (Target t : kAllTargets)
      if (has(request.targets, t)) images.emplace_back(t, target_image(g, t).clone());
    request.targets = static_cast<TargetMask>(Target::Id);
    request.id_samples = true;
    for (IdKind kind : {IdKind::Object, IdKind::Material, IdKind::Cluster}) {
      request.id_kind = kind;
      CryptomatteImage m;
      m.samples = raster.render(camera, Lighting::three_point(), request).id_samples;
      double most = 0;
      cv::minMaxLoc(m.samples, nullptr, &most);
      m.layer.name = "Crypto" + std::to_string(int(kind));
      for (int i = 1; i <= int(most); ++i)
        m.layer.names.push_back("name_" + std::to_string(i));
      mattes.push_back(std::move(m));
    }
  }
};

const Buffers& buffers() {
  static Buffers b;
  return b;
}

uintmax_t folder_bytes(const fs::path& dir) {
  uintmax_t bytes = 0;
  for (const auto& e : fs::directory_iterator(dir))
    bytes += e.file_size();
  return bytes;
}

// 4: exr zip with the three Cryptomatte layers (their id renders not timed).
const char* const kFormats[][2] = {
    {"tiff", "zip"}, {"exr", "zip"}, {"exr", "piz"}, {"exr", "none"}, {"exr", "zip"}};

void BM_WriteBuffers(benchmark::State& state) {
  const Buffers& b = buffers();
  BufferFiles files;
  files.format = kFormats[state.range(0)][0];
  files.compression = kFormats[state.range(0)][1];
  const bool crypto = state.range(0) == 4;
  state.SetLabel(files.format == "tiff"
                     ? "tiff set"
                     : "exr " + files.compression + (crypto ? " cryptomatte" : ""));
  const fs::path dir =
      fs::temp_directory_path() / ("sylva-perf-buffers-" + std::to_string(getpid()));
  fs::create_directories(dir);
  for (auto _ : state)
    write_buffer_files(dir, b.images, b.camera, files,
                       crypto ? b.mattes : std::vector<CryptomatteImage>{});
  state.counters["bytes"] = double(folder_bytes(dir));
  fs::remove_all(dir);
}
BENCHMARK(BM_WriteBuffers)
    ->DenseRange(0, 4)
    ->ArgName("format")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
