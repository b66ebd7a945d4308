// sylva render SCENE [--style S] [view options] [--graph G.dot] -o OUT.png
// sylva buffers SCENE --out-dir DIR [--buffers color,normal,...] [--id KIND] [view options]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/cryptomatte_render.h"
#include "cli/frame.h"
#include "cli/illumination_options.h"
#include "core/error.h"
#include "core/gl/raster_pass.h"
#include "core/io/atomic_file.h"
#include "core/io/buffer_files.h"
#include "core/io/image_io.h"
#include "styles/style.h"

namespace fs = std::filesystem;

namespace sylva::cli {

void check_output_path(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions) {
  fs::path p(path);
  std::string ext = p.extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  bool ok = false;
  std::string allowed;
  for (const std::string& e : extensions) {
    ok = ok || e == ext;
    allowed += (allowed.empty() ? "" : ", ") + e;
  }
  if (!ok) throw InputError(option, "'" + path + "' must end in " + allowed);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(option, "folder of '" + path + "' does not exist");
}

namespace {

void write_graph(const std::string& path, const RenderGraph& graph) {
  if (!path.empty()) write_file_atomic(path, graph.to_dot());
}

// --bit-depth: 0 (the format's own: 16 for TIFF, else 8), or 8 / 16 where the format holds it.
int resolve_bit_depth(int bits, const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool tiff = ext == ".tif" || ext == ".tiff";
  if (bits == 0) return tiff ? 16 : 8;
  if (bits != 8 && bits != 16)
    throw InputError("--bit-depth", "must be 8 or 16, got " + std::to_string(bits));
  if (bits == 16 && !tiff && ext != ".png")
    throw InputError("--bit-depth", "16 bits need a .png or .tiff output, not '" + path + "'");
  return bits;
}

}  // namespace

Action add_render_command(CLI::App& app) {
  struct Opts {
    SceneOptions scene;
    ViewOptions view;
    FoliageRunOptions foliage;
    std::string style = "standard";
    std::vector<std::string> sets;
    std::string out, graph;
    double dpi = 0.0;
    int bit_depth = 0;
  };
  auto o = std::make_shared<Opts>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene in a style to an image");
  add_scene_options(*cmd, o->scene);
  add_view_options(*cmd, o->view);
  add_illumination_options(*cmd, &o->foliage);
  add_style_options(*cmd, o->style, o->sets);
  cmd->add_option("--graph", o->graph, "Also write the render graph as Graphviz .dot");
  cmd->add_option("-o,--output", o->out,
                  "Output image (.png, .jpg, .tiff, or .exr: linear half RGBA, premultiplied), or "
                  "vector lines (.svg or .pdf) of a line style")
      ->required();
  cmd->add_option("--dpi", o->dpi,
                  "Pixels per inch: the page size of .svg/.pdf output in mm/points (0 = px, and "
                  "one point per px in PDF), a .png's pHYs, an .exr's xDensity (0 = none); "
                  "[0, 10000]")
      ->capture_default_str();
  cmd->add_option("--bit-depth", o->bit_depth,
                  "Bits per channel of .png (8 or 16) and .tiff (8 or 16); 0 = 8 for .png, 16 "
                  "for .tiff. 16 holds the styles' 8-bit values widened (x 257)")
      ->capture_default_str();
  return [o, cmd] {
    const std::unique_ptr<Style> style = resolve_style(*cmd, o->style, o->sets);
    const FoliageRun run = foliage_run(o->foliage);
    check_output_path("--output", o->out,
                      {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr", ".svg", ".pdf"});
    const int bit_depth = resolve_bit_depth(o->bit_depth, o->out);
    const bool vector = is_vector_path(o->out);
    if (vector) require_line_style(*style, "--style");
    check_dpi(o->dpi, "--dpi");
    if (!o->graph.empty()) check_output_path("--graph", o->graph, {".dot", ".gv"});
    auto frame = prepare_frame(o->scene, o->view, result_cache_dir(o->foliage));
    const StyledRender r =
        render_styled(sheet_scene(*frame, run, o->scene.seed), *style, vector,
                      [&](const RenderGraph& graph) { write_graph(o->graph, graph); });
    release_frame(frame);
    if (vector)
      write_vector_drawing(o->out, *r.strokes,
                           vector_page(*style, o->view.background == "transparent", o->dpi));
    else
      write_styled_image(o->out, r.image, o->dpi, bit_depth);
    std::printf("wrote %s (%dx%d, style %s)\n", o->out.c_str(), o->view.width, o->view.height,
                style->info().name.c_str());
  };
}

namespace {

struct BuffersOpts {
  SceneOptions scene;
  ViewOptions view;
  FoliageRunOptions foliage;
  std::string normals = "original";
  std::string style = "standard";
  std::vector<std::string> sets;
  std::string dir, list = "color,normal,depth,position,id,ka", graph;
  BufferFiles files;
};

// The command's options; returns --normals (whether it was given decides the normals).
CLI::Option* add_buffers_options(CLI::App& cmd, BuffersOpts& o) {
  add_scene_options(cmd, o.scene);
  add_view_options(cmd, o.view);
  add_illumination_options(cmd, &o.foliage);
  CLI::Option* normals =
      cmd.add_option("--normals", o.normals,
                     "original, realigned (Luft), or realigned-scaled (normal length = ka, Luft "
                     "Fig. 7c); default: the style's");
  add_style_options(cmd, o.style, o.sets);
  cmd.add_option("--out-dir", o.dir, "Output folder (created if its parent exists)")->required();
  cmd.add_option("--buffers", o.list,
                 "Comma-separated: color,normal,depth,position,id,ka,albedo,ao (ao: see ao.model)")
      ->capture_default_str();
  cmd.add_option("--id", o.view.id_kind,
                 "Ids in the id buffer: primitive, cluster, object or material")
      ->capture_default_str();
  cmd.add_option("--format", o.files.format,
                 "tiff: a file per buffer; exr: one multi-channel buffers.exr")
      ->capture_default_str();
  cmd.add_option("--compression", o.files.compression, "EXR compression: none, zip or piz")
      ->capture_default_str();
  cmd.add_option("--cryptomatte", o.files.cryptomatte,
                 "EXR Cryptomatte layers: object, material, asset (leaf clusters), or none")
      ->capture_default_str();
  cmd.add_option("--graph", o.graph, "Also write the render graph as Graphviz .dot");
  return normals;
}

void check_out_dir(const std::string& out_dir) {
  const fs::path dir(out_dir);
  std::error_code ec;
  const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec) && !fs::is_directory(parent, ec))
    throw InputError("--out-dir", "'" + out_dir + "': parent folder does not exist");
}

}  // namespace

Action add_buffers_command(CLI::App& app) {
  auto o = std::make_shared<BuffersOpts>();
  CLI::App* cmd = app.add_subcommand(
      "buffers",
      "Write the G-buffers (lossless TIFF/PNG and 8-bit previews, or one OpenEXR) and camera.json");
  CLI::Option* normals = add_buffers_options(*cmd, *o);
  return [o, cmd, normals] {
    check_buffer_files(o->files);
    const std::vector<std::string> mattes = o->files.format == "exr"
                                                ? parse_cryptomatte_list(o->files.cryptomatte)
                                                : std::vector<std::string>{};
    const TargetMask wanted = parse_buffer_list(o->list);
    check_out_dir(o->dir);
    if (!o->graph.empty()) check_output_path("--graph", o->graph, {".dot", ".gv"});
    const std::unique_ptr<Style> style = resolve_style(*cmd, o->style, o->sets);
    const FoliageRun run = foliage_run(o->foliage);
    const NormalMode mode =
        normals->count() > 0 ? parse_normal_mode(o->normals, "--normals") : style->normals();
    auto frame = prepare_frame(o->scene, o->view, result_cache_dir(o->foliage));
    frame->setup.request.flat_albedo =
        style->params().albedo == AlbedoSource::Flat;  // ids follow --id
    const BufferImages buffers =
        render_buffers(*frame, *style, run, o->scene.seed, mode, wanted,
                       [&](const RenderGraph& graph) { write_graph(o->graph, graph); });
    const Camera camera = frame->setup.camera;
    const std::vector<CryptomatteImage> crypto = render_cryptomattes(*frame, mattes);
    release_frame(frame);
    write_folder_atomic(o->dir, [&](const std::string& staging) {
      write_buffer_files(staging, buffers, camera, o->files, crypto);
    });
    std::printf("wrote %s buffers to %s\n", o->list.c_str(), o->dir.c_str());
  };
}

}  // namespace sylva::cli
