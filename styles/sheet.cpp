#include "styles/sheet.h"

#include "core/gl/instance_draws.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.h"
#include "npr/leaf_pieces.h"
#include "npr/surface_samples.h"

namespace sylva {

namespace {

constexpr size_t kMaxCells = 256;

struct Sweep {
  std::string key;
  std::vector<std::string> values;
};

Sweep parse_sweep(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--sweep", "'" + text + "' is not section.key=v1,v2,...");
  Sweep s;
  s.key = text.substr(0, eq);
  std::stringstream values(text.substr(eq + 1));
  for (std::string v; std::getline(values, v, ',');) {
    if (v.empty()) throw InputError("--sweep", "'" + text + "' has an empty value");
    s.values.push_back(v);
  }
  if (s.values.empty()) throw InputError("--sweep", "'" + text + "' lists no values");
  return s;
}

std::string foliage_key(const Style& style) {
  std::string key;
  for (const ParamSpec& spec : style.set().specs())
    if (spec.key.starts_with("foliage."))
      key += spec.key + "=" + style.set().value_text(spec.key) + ";";
  return key;
}

std::string ao_key(const Style& style) {
  std::string key;
  for (const ParamSpec& spec : style.set().specs())
    if (spec.key.starts_with("ao.")) key += spec.key + "=" + style.set().value_text(spec.key) + ";";
  return key;
}

// What a style asks of the raster pass, as a comparable text.
std::string raster_key(const Style& style, const RasterRequest& request, NormalMode mode,
                       const std::string& foliage) {
  std::ostringstream k;
  k << static_cast<int>(mode) << '|' << request.flat_albedo << '|'
    << static_cast<int>(request.id_kind) << '|' << request.background.r << ','
    << request.background.g << ',' << request.background.b << ',' << request.background.a;
  if (mode != NormalMode::Original) k << '|' << foliage;
  if (style.params().ao.model != AoModel::None) k << '|' << ao_key(style);
  return k.str();
}

}  // namespace

std::vector<SheetEntry> expand_sheet(const std::vector<std::string>& styles,
                                     const std::vector<std::string>& sets,
                                     const std::vector<std::string>& sweeps) {
  if (styles.empty()) throw InputError("--styles", "name at least one style");
  for (const std::string& s : styles)
    if (s.empty()) throw InputError("--styles", "empty style name in the list");
  std::vector<Sweep> parsed;
  for (const std::string& text : sweeps) {
    Sweep s = parse_sweep(text);
    for (const Sweep& other : parsed)
      if (other.key == s.key) throw InputError("--sweep", "'" + s.key + "' is swept twice");
    parsed.push_back(std::move(s));
  }
  size_t cells = styles.size();
  for (const Sweep& s : parsed) {
    cells *= s.values.size();
    if (cells > kMaxCells)
      throw InputError("--sweep",
                       "the sheet would have more than " + std::to_string(kMaxCells) + " cells");
  }
  std::vector<SheetEntry> entries;
  for (const std::string& style : styles) {
    std::vector<size_t> at(parsed.size(), 0);
    for (;;) {
      SheetEntry e;
      e.style = style;
      e.sets = sets;
      for (size_t i = 0; i < parsed.size(); ++i) {
        const std::string a = parsed[i].key + "=" + parsed[i].values[at[i]];
        e.sets.push_back(a);
        e.swept.push_back(a);
      }
      entries.push_back(std::move(e));
      size_t i = parsed.size();
      while (i > 0 && ++at[i - 1] == parsed[i - 1].values.size())
        at[--i] = 0;
      if (i == 0) break;
    }
  }
  return entries;
}

int sheet_columns(size_t n, const std::vector<std::string>& sweeps) {
  SYLVA_CHECK(n >= 1, "sheet_columns: no cells");
  if (!sweeps.empty()) return static_cast<int>(parse_sweep(sweeps.back()).values.size());
  return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)) - 1e-9));
}

std::vector<std::unique_ptr<Style>> build_sheet_styles(const std::vector<SheetEntry>& entries,
                                                       const std::vector<ParamAssignment>& given) {
  std::vector<std::unique_ptr<Style>> styles;
  for (const SheetEntry& e : entries) {
    auto style = std::make_unique<Style>(e.style);
    for (const ParamAssignment& a : given)
      style->set().set(a);
    for (const std::string& a : e.sets)
      apply_assignment(a, style->set(), "--set");
    styles.push_back(std::move(style));
  }
  return styles;
}

std::vector<std::string> changed_parameters(const Style& style,
                                            const std::vector<std::string>& skip) {
  std::vector<std::string> out;
  for (const ParamSpec& spec : style.set().specs()) {
    if (std::find(skip.begin(), skip.end(), spec.key) != skip.end()) continue;
    const std::string value = style.set().value_text(spec.key);
    if (value != spec.default_text) out.push_back(spec.key + "=" + value);
  }
  return out;
}

SheetScene make_sheet_scene(const Scene& scene, const RasterSetup& raster, const FoliageRun& run,
                            uint64_t seed) {
  SheetScene s;
  s.raster = raster;
  s.foliage_diagonal = scene.bounds(Role::Foliage).diagonal();
  s.scene_sphere = scene.framing_sphere();
  s.branch_cluster = scene.branch_cluster_id();
  s.has_foliage = !scene.bounds(Role::Foliage).empty();
  s.scene = &scene;
  s.seed = seed;
  s.foliage = [run, seed, &scene](const FoliageSettings& settings) {
    return foliage_setup(settings, run, seed, scene);
  };
  return s;
}

SheetPlan add_sheet_passes(RenderGraph& graph, const std::vector<const Style*>& styles,
                           const SheetScene& scene, bool present_strokes) {
  SYLVA_CHECK(!styles.empty(), "add_sheet_passes: no styles");
  const bool scoped = styles.size() > 1;
  auto scope = [&](const std::string& name) {
    return scoped ? std::make_unique<GraphScope>(graph, name) : nullptr;
  };
  std::map<std::string, ShadingHandle> foliage;   // foliage key -> vertex-shading
  std::map<std::string, AoShadingHandle> ao;      // ao key -> ao-shading
  std::map<std::string, GBufferHandles> rasters;  // raster key -> its targets
  std::map<std::string, RasterRequest> requests;  // raster key -> its request
  SheetPlan plan;
  // Read by the line styles only (compile() culls it otherwise).
  const SamplesHandle samples =
      scene.scene ? add_surface_samples_pass(graph, scene.scene, scene.samples_memo)
                  : SamplesHandle{};
  const LeafPiecesHandle pieces =
      samples.valid()
          ? add_leaf_pieces_pass(graph, samples, scene.branch_cluster, scene.pieces_memo)
          : LeafPiecesHandle{};
  for (size_t i = 0; i < styles.size(); ++i) {
    const Style& style = *styles[i];
    RasterSetup setup = scene.raster;
    style.configure(setup.request);
    const NormalMode mode = scene.has_foliage ? style.normals() : NormalMode::Original;
    setup.request.scaled_normals = mode == NormalMode::RealignedScaled;
    // Declared for every style, so compile() is what culls the preprocessing of styles that
    // keep the model's normals (and the graph's .dot shows it culled).
    const FoliageSettings settings =
        style.foliage_settings(scene.raster.camera, scene.scene_sphere);
    const std::string fkey = foliage_key(style) + std::to_string(settings.picture_rho);
    if (!foliage.contains(fkey)) {
      auto s = scope("foliage-" + std::to_string(foliage.size()));
      IlluminationSetup luft = scene.foliage(settings);
      luft.parameter_names = foliage_parameter_names(style.set());
      foliage[fkey] = add_foliage_illumination_pass(graph, std::move(luft));
    }
    const std::string rkey = raster_key(style, setup.request, mode, fkey);
    if (!rasters.contains(rkey)) {
      if (mode != NormalMode::Original)
        setup.shading = foliage[fkey];
      else
        setup.own_shading = true;  // another cell's raster pass may have realigned them
      // Only styles with AO read (and so run) the shell fitting; model none adds no node.
      const AoSettings& aos = style.params().ao;
      if (ao_model_of(aos.model) != AoShading::Model::None) {
        SYLVA_CHECK(scene.scene != nullptr, "ao.model needs SheetScene::scene");
        const std::string akey = ao_key(style);
        if (!ao.contains(akey)) {
          auto s = scope("ao-" + std::to_string(ao.size()));
          AoSetup as;
          as.scene = scene.scene;
          as.settings = style.params().ao;
          as.seed = scene.seed;
          as.memo = scene.ao_memo;
          ao[akey] = add_ao_shading_pass(graph, as);
        }
        setup.ao = ao[akey];
      }
      auto s = scope("raster-" + std::to_string(rasters.size()));
      rasters[rkey] = add_raster_pass(graph, setup);
      if (aos.model == AoModel::Raytraced) {
        SYLVA_CHECK(scene.scene != nullptr, "ao.model needs SheetScene::scene");
        rasters[rkey].ao =
            add_raytraced_ao_pass(graph, scene.scene, rasters[rkey].position, rasters[rkey].normal,
                                  setup.camera.view, aos.rays, scene.seed, scene.ao_memo);
      }
      requests[rkey] = setup.request;
    }
    StyleContext context;
    context.lighting = setup.lighting;
    context.view = setup.camera.view;
    context.background = scene.raster.request.background;  // the view's, not the raster's
    context.clear = setup.request.background;
    context.foliage_diagonal = scene.foliage_diagonal;
    context.rasterizer = setup.rasterizer;
    context.camera = setup.camera;
    context.scene_sphere = scene.scene_sphere;
    if (scene.scene && scene.scene->instanced())
      context.shadow_sphere = visible_instances_sphere(*scene.scene, setup.camera);
    context.branch_cluster = scene.branch_cluster;
    context.blobs = scene.blobs;
    context.surface_samples = samples;
    context.leaf_pieces = pieces;
    auto s = scope("cell-" + std::to_string(i));
    const StyleOutput out = style.build(graph, rasters[rkey], context);
    // Vector output needs the strokes only: the raster ink and its composite are culled.
    if (present_strokes && out.strokes.valid())
      graph.present(out.strokes);
    else
      graph.present(out.image);
    plan.outputs.push_back(out.image);
    plan.strokes.push_back(present_strokes ? out.strokes : Handle<StrokeDrawing>{});
    plan.gbuffers.push_back(rasters[rkey]);
  }
  plan.raster_passes = static_cast<int>(rasters.size());
  graph.compile();
  for (const auto& [key, resource] : foliage)
    plan.foliage_passes += graph.is_live(resource) ? 1 : 0;
  return plan;
}

}  // namespace sylva
