// Contact sheets (DESIGN.md §2): several styles, or one style with swept parameters, rendered
// from one scene in one render graph. Styles that ask the same of the raster pass share it
// (same normals, id kind, albedo and clear colour), styles with the same foliage.* settings
// share the Luft preprocessing, and each style's image passes get a graph scope of their
// own. `sylva render` is the one-style case of the same plan.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "styles/style.h"

namespace sylva {
struct AoMemo;             // npr/ao_pass.h
struct SurfaceSampleMemo;  // npr/surface_samples.h
struct LeafPieceMemo;      // npr/leaf_pieces.h
}  // namespace sylva

namespace sylva {

struct SheetEntry {
  std::string style;               // built-in preset name or .toml path
  std::vector<std::string> sets;   // "section.key=value", applied after the preset in order
  std::vector<std::string> swept;  // this cell's sweep assignments (also the last of `sets`)
};

// The --styles list times the cartesian product of the sweeps ("section.key=v1,v2,..."; the
// last sweep varies fastest). `sets` (the --set overrides) come before a cell's sweep values.
// Throws InputError("--styles" / "--sweep", ...) for an empty list or value, a sweep without
// '=' or values, a key swept twice, or more than 256 cells; the values themselves are checked
// when the styles are built.
std::vector<SheetEntry> expand_sheet(const std::vector<std::string>& styles,
                                     const std::vector<std::string>& sets,
                                     const std::vector<std::string>& sweeps);

// Cells per row: the value count of the last sweep when there is one (so a two-key sweep is
// a table, Luft Fig. 3), else ceil(sqrt(n)). n >= 1.
int sheet_columns(size_t n, const std::vector<std::string>& sweeps);

// The builds of `entries` with `given` (e.g. the CLI's foliage options, which name themselves
// in errors) applied between the preset and the entry's sets. Throws InputError.
std::vector<std::unique_ptr<Style>> build_sheet_styles(const std::vector<SheetEntry>& entries,
                                                       const std::vector<ParamAssignment>& given);

// "key=value" for every parameter the style holds at another value than the built-in
// default, in `sylva styles` order; keys in `skip` are left out.
std::vector<std::string> changed_parameters(const Style& style,
                                            const std::vector<std::string>& skip = {});

// What every cell shares: the uploaded scene and view.
struct SheetScene {
  RasterSetup raster;           // rasteriser, camera, lighting; request = the view's base request
  float foliage_diagonal = 0;   // scene units (StyleContext::foliage_diagonal)
  Sphere scene_sphere;          // StyleContext::scene_sphere
  uint32_t branch_cluster = 0;  // StyleContext::branch_cluster
  // Whether the scene has foliage: without, styles that ask for realigned normals draw the
  // model's (there is no crown to realign them to) instead of failing.
  bool has_foliage = true;
  std::shared_ptr<const BlobSet> blobs;  // StyleContext::blobs
  // The Luft preprocessing for one style's foliage settings; make_sheet_scene's resolves them
  // with foliage_setup (npr/illumination_pass.h). A hook, so that frames of one scene can
  // share one preprocessing (memoize_preprocessing) and tests can supply a fixed one.
  std::function<IlluminationSetup(const FoliageSettings&)> foliage;
  // For styles with ao.model other than none: the scene the AO shells are fitted to (outlives
  // execute()) and the seed of the fit.
  const Scene* scene = nullptr;
  uint64_t seed = 1;
  // Set for many frames of one scene (memoize_preprocessing): the AO shells and the ray
  // tracer's BVH are computed once and shared. Null: per graph.
  std::shared_ptr<AoMemo> ao_memo;
  // Set for many frames of one scene: the surface samples of the ink lines' crown coverage
  // are made once. Null: per graph.
  std::shared_ptr<SurfaceSampleMemo> samples_memo;
  // Likewise the foliage's drawing primitives (npr/leaf_pieces.h). Null: per graph.
  std::shared_ptr<LeafPieceMemo> pieces_memo;
};

// Every field for `scene` (outlives the sheet) seen through `raster`; the preprocessing of
// each style's foliage settings runs with `run`'s cache and outputs, seeded by `seed`.
SheetScene make_sheet_scene(const Scene& scene, const RasterSetup& raster, const FoliageRun& run,
                            uint64_t seed);

struct SheetPlan {
  std::vector<ImageHandle> outputs;  // per style: its final image (CV_8UC4 BGRA sRGB), presented
  // per style: its StrokeDrawing (StyleOutput::strokes), presented with `present_strokes`,
  // else none
  std::vector<Handle<StrokeDrawing>> strokes;
  std::vector<GBufferHandles> gbuffers;  // per style: the raster pass it reads
  int raster_passes = 0;                 // distinct raster configurations
  int foliage_passes = 0;                // Luft preprocessings that run (distinct settings read)
};

// Adds the passes of every style to `graph`, presents their images and compiles. With one style
// nothing is scoped (pass names as in a plain render); with several, style i's passes live
// in scope "cell-i", raster configuration j in "raster-j", foliage settings k in
// "foliage-k", AO settings m in "ao-m".
// With present_strokes, every style made of lines presents its StrokeDrawing instead of its
// image (vector output: the raster ink is culled).
SheetPlan add_sheet_passes(RenderGraph& graph, const std::vector<const Style*>& styles,
                           const SheetScene& scene, bool present_strokes = false);

}  // namespace sylva
