#include "cli/frame.h"

#include <malloc.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/io/exr_writer.h"
#include "core/io/image_io.h"
#include "core/io/pdf_writer.h"
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
  f->context = create_gl_context();
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
      ->capture_default_str();
  cmd.add_option("--set", sets,
                 "Override a style parameter: section.key=value (repeatable; see sylva styles)");
}

std::unique_ptr<Style> resolve_style(const CLI::App& cmd, const std::string& name,
                                     const std::vector<std::string>& sets,
                                     IlluminationOptions& io) {
  auto style = std::make_unique<Style>(name, sets);
  apply_explicit_illumination_options(cmd, style->set());
  const IlluminationOptions run = io;
  io = style->params().foliage;
  io.surface_out = run.surface_out;
  io.no_cache = run.no_cache;
  io.cache_dir = run.cache_dir;
  return style;
}

SheetScene sheet_scene(const Frame& frame, const IlluminationOptions& run, uint64_t seed) {
  SheetScene s;
  s.raster = frame.setup;
  s.foliage_diagonal = frame.scene.bounds(Role::Foliage).diagonal();
  s.scene_sphere = frame.scene.framing_sphere();
  s.branch_cluster = frame.scene.branch_cluster_id();
  s.has_foliage = !frame.scene.bounds(Role::Foliage).empty();
  const Scene* scene = &frame.scene;
  s.scene = scene;
  s.seed = seed;
  s.foliage = [run, seed, scene](const FoliageSettings& settings) {
    IlluminationOptions io = settings;
    io.surface_out = run.surface_out;
    io.no_cache = run.no_cache;
    io.cache_dir = run.cache_dir;
    return illumination_setup(io, seed, *scene);
  };
  return s;
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

VectorPage vector_page(const Style& style, const ViewOptions& view, double dpi) {
  VectorPage page;
  page.dpi = dpi;
  const InkParams& ink = style.params().ink;
  if (ink.transparent || view.background == "transparent")
    page.paper.reset();
  else
    page.paper = ink.paper.color;
  return page;
}

void write_vector_drawing(const std::string& path, const StrokeDrawing& d, const VectorPage& page) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".pdf")
    write_pdf(path, d, page);
  else
    write_svg(path, d, page);
}

void write_styled_image(const std::string& path, const cv::Mat& bgra, double dpi, int bit_depth) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".jpg" || ext == ".jpeg") {
    cv::Mat bgr;
    cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
    write_image(path, bgr);
    return;
  }
  if (ext == ".exr") {
    ExrImage exr;
    add_exr_colour(exr, bgra, "");
    exr.dpi = dpi;
    write_exr(path, exr);
    return;
  }
  if (bit_depth == 16) {
    cv::Mat wide;
    bgra.convertTo(wide, CV_16U, 257.0);  // 255 -> 65535
    write_image(path, wide, dpi);
    return;
  }
  write_image(path, bgra, dpi);
}

}  // namespace sylva::cli
