#include "cli/frame.h"

#include <filesystem>

namespace fs = std::filesystem;

namespace sylva::cli {

std::unique_ptr<Frame> prepare_frame(const SceneOptions& so, ViewOptions& vo,
                                     const std::string& cache_dir) {
  resolve_view_options(vo);  // bad view options fail before the scene loads
  return make_frame(load_scene_for_cli(so), vo, cache_dir);
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

}  // namespace sylva::cli
