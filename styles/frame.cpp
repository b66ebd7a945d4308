#include "styles/frame.h"

#include <malloc.h>

#include <cstdio>
#include <sstream>

#include "core/cache/result_cache.h"
#include "core/error.h"
#include "npr/ao_pass.h"
#include "npr/foliage_settings.h"
#include "npr/leaf_pieces.h"
#include "npr/plant_lod.h"
#include "npr/surface_samples.h"
#include "styles/presets.h"

namespace sylva {

std::unique_ptr<Frame> make_frame(Scene scene, ViewOptions& vo, const std::string& cache_dir) {
  resolve_view_options(vo);
  auto f = std::make_unique<Frame>();
  f->scene = std::move(scene);
  apply_ground_option(f->scene, vo);
  f->setup.camera = view_camera(f->scene, vo);
  f->context = start_gl(vo);
  f->rasterizer = std::make_unique<Rasterizer>(*f->context);
  f->rasterizer->upload(f->scene);
  if (vo.lod == "on" && f->scene.instanced()) {
    const ResultCache cache(cache_dir);
    f->rasterizer->set_lod(f->scene, scene_lods(f->scene, cache_dir.empty() ? nullptr : &cache));
  }
  f->setup.rasterizer = f->rasterizer.get();
  set_frame_view(*f, vo);
  return f;
}

void set_frame_view(Frame& frame, ViewOptions& vo) {
  resolve_view_options(vo);
  frame.setup.camera = view_camera(frame.scene, vo);
  frame.setup.lighting = lighting_for(vo);
  frame.setup.request = raster_request(vo);
}

void release_frame(std::unique_ptr<Frame>& frame) {
  frame.reset();
  malloc_trim(0);
}

void require_line_style(const Style& style, const std::string& option) {
  if (style.has_strokes()) return;
  std::string names;
  for (const std::string& n : builtin_preset_names())
    if (Style(n).has_strokes()) names += (names.empty() ? "" : ", ") + n;
  throw InputError(option, "style '" + style.info().name +
                               "' draws no lines, so it has no vector output (.svg, .pdf); "
                               "styles made of lines: " +
                               names + ", or a preset inheriting them");
}

StyledRender render_styled(const SheetScene& scene, const Style& style, bool strokes,
                           const std::function<void(const RenderGraph&)>& on_compiled) {
  RenderGraph graph;
  const SheetPlan plan = add_sheet_passes(graph, {&style}, scene, strokes);
  graph.compile();
  if (on_compiled) on_compiled(graph);
  graph.execute();
  StyledRender out;
  if (strokes)
    out.strokes = std::make_shared<const StrokeDrawing>(graph.get<StrokeDrawing>(plan.strokes[0]));
  else
    out.image = graph.get<cv::Mat>(plan.outputs[0]);
  return out;
}

TargetMask parse_buffer_list(const std::string& list) {
  TargetMask wanted = 0;
  std::stringstream ss(list);
  for (std::string name; std::getline(ss, name, ',');) {
    bool found = false;
    for (Target t : kAllTargets)
      if (name == target_name(t)) {
        wanted |= static_cast<TargetMask>(t);
        found = true;
      }
    if (!found) {
      std::string allowed;
      for (Target t : kAllTargets)
        allowed += (allowed.empty() ? "" : ", ") + std::string(target_name(t));
      throw InputError("--buffers", "unknown buffer '" + name + "' (allowed: " + allowed + ")");
    }
  }
  if (wanted == 0) throw InputError("--buffers", "name at least one buffer");
  return wanted;
}

namespace {

// The raster pass, fed by the Luft preprocessing node when `mode` asks for it; the node is
// always declared, so compile() is what culls it for the original normals.
// With ao.model other than none, the AO shell node feeds it too (not declared otherwise).
GBufferHandles add_buffer_passes(RenderGraph& graph, Frame& frame, IlluminationSetup luft,
                                 uint64_t seed, NormalMode mode, const AoSettings& ao) {
  const ShadingHandle shading = add_foliage_illumination_pass(graph, std::move(luft));
  RasterSetup setup = frame.setup;
  if (mode != NormalMode::Original) setup.shading = shading;
  if (ao_model_of(ao.model) != AoShading::Model::None) {
    AoSetup as;
    as.scene = &frame.scene;
    as.settings = ao;
    as.seed = seed;
    setup.ao = add_ao_shading_pass(graph, as);
  }
  setup.request.scaled_normals = mode == NormalMode::RealignedScaled;
  GBufferHandles gb = add_raster_pass(graph, setup);
  if (ao.model == AoModel::Raytraced)
    gb.ao = add_raytraced_ao_pass(graph, &frame.scene, gb.position, gb.normal, setup.camera.view,
                                  ao.rays, seed);
  return gb;
}

// Every foliage.* value as text, and the picture-scale rho exactly.
std::string foliage_settings_key(const FoliageSettings& settings) {
  FoliageSettings bound = settings;
  ParamSet set;
  bind_foliage_params(set, bound);
  std::string key;
  for (const ParamSpec& spec : set.specs())
    key += spec.key + "=" + set.value_text(spec.key) + ";";
  char rho[64];
  std::snprintf(rho, sizeof rho, "picture_rho=%a", settings.picture_rho);
  return key + rho;
}

}  // namespace

BufferImages render_buffers(Frame& frame, const Style& style, const FoliageRun& run, uint64_t seed,
                            NormalMode mode, TargetMask wanted,
                            const std::function<void(const RenderGraph&)>& on_done,
                            FrameMemos* memos) {
  // With the style's picture-scale rho (ink.detail), as its render would use.
  const FoliageSettings settings =
      style.foliage_settings(frame.setup.camera, frame.scene.framing_sphere());
  IlluminationSetup luft = foliage_setup(settings, run, seed, frame.scene);
  luft.parameter_names = foliage_parameter_names(style.set());
  if (memos) luft.memo = foliage_memo(*memos, settings);
  RenderGraph graph;
  const GBufferHandles gb =
      add_buffer_passes(graph, frame, std::move(luft), seed, mode, style.params().ao);
  for (Target t : kAllTargets)
    if (has(wanted, t)) graph.present(gb.of(t));
  graph.compile();
  graph.execute();
  if (on_done) on_done(graph);
  BufferImages buffers;
  for (Target t : kAllTargets)
    if (has(wanted, t)) buffers.emplace_back(t, graph.get(gb.of(t)));
  return buffers;
}

FrameMemos::FrameMemos()
    : ao(std::make_shared<AoMemo>()),
      samples(std::make_shared<SurfaceSampleMemo>()),
      pieces(std::make_shared<LeafPieceMemo>()) {}

std::shared_ptr<std::shared_ptr<const VertexShading>> foliage_memo(
    FrameMemos& memos, const FoliageSettings& settings) {
  const std::string key = foliage_settings_key(settings);
  const std::lock_guard lock(memos.mutex);
  auto& slot = memos.foliage[key];
  if (!slot) {
    slot = std::make_shared<std::shared_ptr<const VertexShading>>();
    memos.foliage_order.push_back(key);
    if (memos.foliage_order.size() > FrameMemos::kFoliageMemos) {
      memos.foliage.erase(memos.foliage_order.front());
      memos.foliage_order.erase(memos.foliage_order.begin());
    }
  }
  return memos.foliage[key];
}

void share_memos(SheetScene& scene, const std::shared_ptr<FrameMemos>& memos) {
  scene.ao_memo = memos->ao;
  scene.samples_memo = memos->samples;
  scene.pieces_memo = memos->pieces;
  scene.foliage = [f = scene.foliage, memos](const FoliageSettings& settings) {
    IlluminationSetup setup = f(settings);
    setup.memo = foliage_memo(*memos, settings);
    return setup;
  };
}

}  // namespace sylva
