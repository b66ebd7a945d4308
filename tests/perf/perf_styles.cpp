// Benchmarks for the styles (issue "Styles"): one frame of each built-in preset at 1024² on
// the 100k-leaf sample tree, through the render graph as `sylva render` builds it (raster
// pass + the style's image passes), against the bare raster pass (colour only) of the same
// scene; toon also with cast shadows (its shadow-map pass included). The Luft preprocessing is
// scene-level and cached (npr/foliage_cache.h), so it is computed once outside the timed loop.
// Reports medians (run with --benchmark_repetitions); the cost ratios to the bare raster pass are
// worked out from them. The line styles (raster, ink, pen) also on the shared weeping willow.
// The surface samples and the foliage's pieces the ink styles read are scene-level too (made
// once per scene, shared by a turntable's frames): made in the first iteration, then memoised.
//
// The same for the ink style on a small alpha-card tree (`sylva sample tree --leaves 4200`,
// 25,013 triangles, loaded back from a .glb as the command does): one frame (BM_CardTree), and
// everything `sylva render cards.glb --style ink --size 1024x1024` does in-process with a
// warm result cache (BM_CardTreeCommand: load, clusters, GL context, upload, cached
// preprocessing, raster, ink, PNG or SVG written), which leaves out only the process start; the
// command also on the shared willow (BM_WillowCommand).
#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>

#include "core/gl/raster_pass.h"
#include "core/io/image_io.h"
#include "core/io/svg_writer.h"
#include "core/scene/gltf_write.h"
#include "core/scene/load.h"
#include "npr/foliage_illumination.h"
#include "npr/illumination_pass.h"
#include "npr/leaf_clusters.h"
#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"
#include "styles/style.h"
#include "tests/perf/perf_trees.h"

namespace sylva {
namespace {

constexpr int kLeaves = 100'000;
constexpr int kCardLeaves = 4'200;  // 25,013 triangles with the default seed
constexpr int kSize = 1024;

namespace fs = std::filesystem;

struct Rig {
  Scene scene;
  std::unique_ptr<GlContext> context = create_gl_context();
  std::unique_ptr<Rasterizer> raster;
  std::shared_ptr<const VertexShading> shading;
  Camera camera;
  // The scene's foliage diagonal and framing sphere: made once, as a turntable makes them
  // (styles/sheet.cpp make_sheet_scene), not in each frame.
  double foliage_diagonal = 0.0;
  Sphere scene_sphere;
  // Scene-level, made once (as a turntable's frames share them): the surface samples and the
  // foliage's pieces the ink styles project each frame.
  std::shared_ptr<SurfaceSampleMemo> samples = std::make_shared<SurfaceSampleMemo>();
  std::shared_ptr<LeafPieceMemo> pieces = std::make_shared<LeafPieceMemo>();
  explicit Rig(Scene s) : scene(std::move(s)) {
    assign_clusters(scene, ClusterOptions{});
    raster = std::make_unique<Rasterizer>(*context);
    raster->upload(scene);
    shading = std::make_shared<const VertexShading>(vertex_shading(
        compute_foliage_illumination(scene, FoliageParams{}), KaEncoding::Attribute));
    foliage_diagonal = scene.bounds(Role::Foliage).diagonal();
    scene_sphere = scene.framing_sphere();
    camera = make_orbit_camera(scene_sphere, OrbitParams{}, kSize, kSize);
  }
};

Rig& rig() {
  static Rig r(perf::sample_tree(kLeaves));
  return r;
}

// A scratch folder for the card tree's .glb, the result cache and the output image, removed
// at exit.
struct CardFiles {
  fs::path dir = fs::temp_directory_path() / ("sylva-perf-styles-" + std::to_string(getpid()));
  fs::path glb = dir / "cards.glb";
  fs::path cache = dir / "cache";
  fs::path png = dir / "cards-ink.png";
  fs::path svg = dir / "cards-ink.svg";
  CardFiles() {
    fs::create_directories(dir);
    write_glb(perf::sample_tree(kCardLeaves), glb.string());
  }
  ~CardFiles() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

CardFiles& card_files() {
  static CardFiles f;
  return f;
}

Rig& card_rig() {
  static Rig r(load_scene(card_files().glb.string()));
  return r;
}

// One frame of `style` ("raster": the bare raster pass) through the render graph.
void render_frame(Rig& r, const std::string& name, const Style& style) {
  RenderGraph graph;
  RasterSetup setup;
  setup.rasterizer = r.raster.get();
  setup.camera = r.camera;
  setup.lighting = Lighting::three_point();
  style.configure(setup.request);
  if (style.normals() != NormalMode::Original) {
    const auto shading = graph.resource<std::shared_ptr<const VertexShading>>("vertex-shading");
    graph.add_pass("cached-shading", {}, {shading},
                   [&r, shading](PassContext& ctx) { ctx.write(shading, r.shading); });
    setup.shading = shading;
    setup.request.scaled_normals = style.normals() == NormalMode::RealignedScaled;
  }
  // The scene's samples and pieces before the raster, as styles/sheet.cpp adds them: the passes
  // that need no raster run while it draws.
  StyleContext context;
  context.surface_samples = add_surface_samples_pass(graph, &r.scene, r.samples);
  context.branch_cluster = r.scene.branch_cluster_id();
  context.leaf_pieces =
      add_leaf_pieces_pass(graph, context.surface_samples, context.branch_cluster, r.pieces);
  const GBufferHandles gb = add_raster_pass(graph, setup);
  context.lighting = setup.lighting;
  context.view = setup.camera.view;
  context.background = setup.request.background;
  context.foliage_diagonal = r.foliage_diagonal;
  context.rasterizer = r.raster.get();  // toon.cast_shadows renders the key light's shadow map
  context.scene_sphere = r.scene_sphere;
  context.camera = setup.camera;
  const ImageHandle out = name == "raster" ? gb.color : style.build(graph, gb, context).image;
  graph.present(out);
  graph.execute();
  benchmark::DoNotOptimize(graph.get<cv::Mat>(out).data);
}

double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Frames of `style`, with the CPU time of every thread of the process per frame ("cpu_ms"): on a
// machine of few cores the frame's wall time is that work spread over them, and less noisy.
void render_frames(benchmark::State& state, Rig& r, const std::string& name, const Style& style) {
  const double cpu0 = process_cpu_ms();
  for (auto _ : state)
    render_frame(r, name, style);
  state.counters["cpu_ms"] =
      benchmark::Counter((process_cpu_ms() - cpu0) / double(state.iterations()));
}

const char* const kStyles[] = {"raster", "standard", "expressive", "ink",
                               "pen",    "toon",     "watercolor", "toon-shadows"};

// "toon-shadows": toon with toon.cast_shadows (a shadow map from the key light each frame).
Style make_style(const std::string& name) {
  if (name == "raster") return Style("standard");
  if (name == "toon-shadows") return Style("toon", {"toon.cast_shadows=true"});
  return Style(name);
}

void BM_Style(benchmark::State& state) {
  Rig& r = rig();
  const std::string name = kStyles[state.range(0)];
  state.SetLabel(name);
  const Style style = make_style(name);
  render_frames(state, r, name, style);
}
BENCHMARK(BM_Style)
    ->DenseRange(0, 7)
    ->ArgName("style")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The shared weeping willow (218,072 triangles, 63,200 leaves): ink and pen against the raster.
Rig& willow_rig() {
  static Rig r(load_scene(std::string(SYLVA_SHARED_DIR) + "/assets/sapling_weeping_willow_s2.glb"));
  return r;
}

const char* const kLineStyles[] = {"raster", "ink", "pen"};

void BM_Willow(benchmark::State& state) {
  Rig& r = willow_rig();
  const std::string name = kLineStyles[state.range(0)];
  state.SetLabel(name);
  const Style style(name == "raster" ? "standard" : name);
  render_frames(state, r, name, style);
}
BENCHMARK(BM_Willow)
    ->DenseRange(0, 2)
    ->ArgName("style")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

const char* const kCardStyles[] = {"raster", "ink"};

void BM_CardTree(benchmark::State& state) {
  Rig& r = card_rig();
  const std::string name = kCardStyles[state.range(0)];
  state.SetLabel(name);
  const Style style(name == "raster" ? "standard" : name);
  for (auto _ : state)
    render_frame(r, name, style);
}
BENCHMARK(BM_CardTree)
    ->DenseRange(0, 1)
    ->ArgName("style")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// As cli/cmd_render.cpp: the scene at `glb` loaded and clustered, a new GL context, the
// preprocessing through the result cache (filled before the timed loop), the frame, the PNG or
// SVG (into the scratch folder).
void render_command(const fs::path& glb, const CardFiles& files, const Style& style, bool svg) {
  Scene scene = load_scene(glb.string());
  assign_clusters(scene, ClusterOptions{});
  const std::unique_ptr<GlContext> context = create_gl_context();
  Rasterizer raster(*context);
  raster.upload(scene);
  RenderGraph graph;
  IlluminationSetup illumination;
  illumination.scene = &scene;
  illumination.cache_dir = files.cache.string();
  RasterSetup setup;
  setup.rasterizer = &raster;
  setup.camera = make_orbit_camera(scene.framing_sphere(), OrbitParams{}, kSize, kSize);
  setup.lighting = Lighting::three_point();
  style.configure(setup.request);
  setup.shading = add_foliage_illumination_pass(graph, illumination);
  setup.request.scaled_normals = style.normals() == NormalMode::RealignedScaled;
  const GBufferHandles gb = add_raster_pass(graph, setup);
  StyleContext context_info;
  context_info.lighting = setup.lighting;
  context_info.view = setup.camera.view;
  context_info.background = setup.request.background;
  context_info.foliage_diagonal = scene.bounds(Role::Foliage).diagonal();
  context_info.camera = setup.camera;
  context_info.scene_sphere = scene.framing_sphere();
  context_info.branch_cluster = scene.branch_cluster_id();
  const StyleOutput out = style.build(graph, gb, context_info);
  if (svg)
    graph.present(out.strokes);
  else
    graph.present(out.image);
  graph.execute();
  if (svg)
    write_svg(files.svg.string(), graph.get<StrokeDrawing>(out.strokes), VectorPage{});
  else
    write_image(files.png.string(), graph.get<cv::Mat>(out.image));
}

// `sylva render GLB --style ink`: arg 0 `-o x.png`, 1 `-o x.svg` (issue "Vector line art": the
// SVG at most 1.3x the PNG).
void run_command(benchmark::State& state, const fs::path& glb) {
  const CardFiles& files = card_files();
  const Style style("ink");
  const bool svg = state.range(0) == 1;
  state.SetLabel(svg ? "ink svg" : "ink png");
  render_command(glb, files, style, svg);  // fills the result cache, as a first run would
  for (auto _ : state)
    render_command(glb, files, style, svg);
}

void BM_CardTreeCommand(benchmark::State& state) {
  run_command(state, card_files().glb);
}
BENCHMARK(BM_CardTreeCommand)
    ->DenseRange(0, 1)
    ->ArgName("svg")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same on the shared weeping willow.
void BM_WillowCommand(benchmark::State& state) {
  run_command(state, fs::path(SYLVA_SHARED_DIR) / "assets/sapling_weeping_willow_s2.glb");
}
BENCHMARK(BM_WillowCommand)
    ->DenseRange(0, 1)
    ->ArgName("svg")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace sylva

BENCHMARK_MAIN();
