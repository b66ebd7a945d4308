#include "cli/frame.h"

#include <malloc.h>

#include <filesystem>

#include "core/error.h"
#include "npr/plant_lod.h"
#include "styles/presets.h"

namespace fs = std::filesystem;

namespace sylva::cli {

std::unique_ptr<Frame> prepare_frame(const SceneOptions& so, ViewOptions& vo,
                                     const std::string& cache_dir) {
  resolve_view_options(vo);
  auto f = std::make_unique<Frame>();
  f->scene = load_scene_for_cli(so);
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
  f->setup.lighting = lighting_for(vo);
  f->setup.request = raster_request(vo);
  return f;
}

void release_frame(std::unique_ptr<Frame>& frame) {
  frame.reset();
  malloc_trim(0);
}

void add_style_options(CLI::App& cmd, std::string& style, std::vector<std::string>& sets) {
  cmd.add_option("--style", style, "A built-in style (sylva styles) or a preset file .toml")
      ->capture_default_str()
      ->group(kStyleGroup);
  cmd.add_option("--set", sets,
                 "Override a style parameter: section.key=value (repeatable; see sylva styles)")
      ->group(kStyleGroup);
}

std::unique_ptr<Style> resolve_style(const CLI::App& cmd, const std::string& name,
                                     const std::vector<std::string>& sets) {
  auto style = std::make_unique<Style>(name, sets);
  apply_foliage_options(cmd, style->set());
  return style;
}

SheetScene sheet_scene(const Frame& frame, const FoliageRun& run, uint64_t seed) {
  return make_sheet_scene(frame.scene, frame.setup, run, seed);
}

bool is_vector_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".svg" || ext == ".pdf";
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

}  // namespace sylva::cli
