#include "cli/frame.h"

#include <malloc.h>

#include <opencv2/imgproc.hpp>

#include "core/gl/depth_range.h"
#include "core/io/image_io.h"

namespace sylva::cli {

std::unique_ptr<Frame> prepare_frame(const SceneOptions& so, ViewOptions& vo) {
  resolve_view_options(vo);
  auto f = std::make_unique<Frame>();
  f->scene = load_scene_for_cli(so);
  apply_ground_option(f->scene, vo);
  f->setup.camera = make_orbit_camera(f->scene.framing_sphere(), vo.orbit, vo.width, vo.height);
  fit_camera_depth(f->setup.camera, f->scene);
  f->context = create_gl_context();
  f->rasterizer = std::make_unique<Rasterizer>(*f->context);
  f->rasterizer->upload(f->scene);
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

void write_styled_image(const std::string& path, const cv::Mat& bgra) {
  if (path.ends_with(".jpg") || path.ends_with(".jpeg")) {
    cv::Mat bgr;
    cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
    write_image(path, bgr);
    return;
  }
  write_image(path, bgra);
}

}  // namespace sylva::cli
