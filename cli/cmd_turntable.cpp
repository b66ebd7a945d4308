// sylva turntable SCENE --style S --frames N [--degrees 360] [--axis y] [--zoom Z] [--fps F]
//   [--keyframe-every n] [--keyframe-cache DIR] [--frame-range A:B] [--resume]
//   [--report coherence.csv] -o OUT.mp4|OUT.gif|DIR/
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/frame.h"
#include "cli/video_out.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/gif_writer.h"
#include "core/io/image_io.h"
#include "core/progress.h"
#include "npr/blob_keyframes.h"
#include "styles/turntable.h"
#include "styles/turntable_frames.h"

namespace fs = std::filesystem;

namespace sylva::cli {

namespace {

std::string frame_name(int frame, const std::string& format = "png") {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%05d.%s", frame, format.c_str());
  return name;
}

// Everything a keyframe's blobs depend on, for --keyframe-cache: the scene, the frame-0 camera,
// the image, the path, the interval and the blobs.* settings.
std::string keyframe_signature(const Frame& frame, const Style& style, const TurntablePath& path,
                               int every) {
  std::ostringstream s;
  s.precision(9);
  s << "sylva blob keyframes v1; source " << frame.scene.report.source << "; triangles "
    << frame.scene.triangle_count() << "; clusters " << frame.scene.max_cluster_id() << "; size "
    << frame.setup.camera.width << 'x' << frame.setup.camera.height << "; ssaa "
    << frame.setup.request.ssaa << "; frames " << path.frames << "; degrees " << path.degrees
    << "; axis " << path.axis << "; zoom " << path.zoom << "; every " << every << "; view";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      s << ' ' << frame.setup.camera.view[c][r] << ' ' << frame.setup.camera.proj[c][r];
  for (const ParamSpec& spec : style.set().specs())
    if (spec.key.starts_with("blobs."))
      s << "; " << spec.key << '=' << style.set().value_text(spec.key);
  return s.str();
}

}  // namespace

Action add_turntable_command(CLI::App& app) {
  struct Opts {
    SceneOptions scene;
    ViewOptions view;
    IlluminationOptions illumination;
    std::string style = "standard";
    std::vector<std::string> sets;
    TurntablePath path;
    std::string axis = "y";
    double fps = 30;
    std::string range, report, out, keyframe_cache, frame_format = "png";
    double dpi = 0.0;
    int keyframe_every = 1;
    bool resume = false, quiet = false;
  };
  auto o = std::make_shared<Opts>();
  o->view.size = "512x512";
  CLI::App* cmd = app.add_subcommand(
      "turntable",
      "Render a turntable animation in a style: an MP4, a GIF or a folder of PNG frames");
  add_scene_options(*cmd, o->scene);
  add_view_options(*cmd, o->view);
  add_illumination_options(*cmd, o->illumination);
  add_style_options(*cmd, o->style, o->sets);
  cmd->add_option("--frames", o->path.frames, "Number of frames, [1, 100000]")
      ->capture_default_str();
  cmd->add_option("--degrees", o->path.degrees,
                  "Rotation over all frames in degrees, [-36000, 36000]; 360 loops seamlessly")
      ->capture_default_str();
  cmd->add_option("--axis", o->axis, "World axis to turn about: x, y (up) or z")
      ->capture_default_str();
  cmd->add_option("--zoom", o->path.zoom, "Image magnification, (0, 100]; 1 = framed")
      ->capture_default_str();
  cmd->add_option("--fps", o->fps,
                  "Frames per second of the MP4 or GIF, [1, 240] (a GIF stores whole hundredths of "
                  "a second)")
      ->capture_default_str();
  cmd->add_option("--frame-range", o->range,
                  "Render frames A to B-1 only (A:B, 0-based; folder output), e.g. for a "
                  "render farm; the frames equal those of a full run");
  cmd->add_flag("--resume", o->resume, "Skip frames already in the output folder");
  cmd->add_option("--keyframe-every", o->keyframe_every,
                  "blobs style: shrink-wrap the blobs every n-th frame and interpolate the "
                  "frames between (Dudley §5.1); >= 1, 1 = every frame")
      ->capture_default_str();
  cmd->add_option("--keyframe-cache", o->keyframe_cache,
                  "blobs style: keep the keyframes' blobs in this folder and reuse them (e.g. "
                  "across the jobs of a --frame-range split)");
  cmd->add_option("--report", o->report,
                  "Write per-frame time and flicker (mean |change| inside the plant, 8-bit "
                  "levels) to a .csv");
  cmd->add_option("--frame-format", o->frame_format,
                  "Folder output: png, exr (linear half RGBA, premultiplied, for compositing), or "
                  "svg / pdf (the strokes of a line style: ink, pen) for plotters and motion work")
      ->capture_default_str();
  cmd->add_option("--dpi", o->dpi,
                  "Folder frames: pixels per inch (svg/pdf page size, png pHYs, exr xDensity), "
                  "[0, 10000]")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "No progress output");
  cmd->add_option(
         "-o,--output", o->out,
         "Output .mp4, .gif, or a folder for frames frame-00000.png, ... (or .exr/.svg/.pdf "
         "with --frame-format; a name without extension)")
      ->required();
  return [o, cmd] {
    o->path.axis = o->axis.size() == 1 ? o->axis[0] : '?';
    validate_turntable(o->path);
    if (!(o->fps >= 1 && o->fps <= 240)) throw InputError("--fps", "must be in [1, 240]");
    // A folder: "out/", an existing folder, or a name without an extension.
    const bool to_dir =
        o->out.ends_with("/") || fs::is_directory(o->out) || fs::path(o->out).extension().empty();
    if (!to_dir) {
      check_output_path("--output", o->out, {".mp4", ".gif"});
      if (!o->range.empty())
        throw InputError("--frame-range", "needs a folder output (an MP4 or GIF is written whole)");
      if (o->resume) throw InputError("--resume", "needs a folder output");
    } else {
      fs::path dir = fs::path(o->out).lexically_normal();
      if (!dir.has_filename()) dir = dir.parent_path();  // "out/" -> "out"
      const fs::path parent = dir.parent_path();
      std::error_code ec;
      if (!fs::is_directory(dir, ec) && !parent.empty() && !fs::is_directory(parent, ec))
        throw InputError("--output", "parent folder of '" + o->out + "' does not exist");
    }
    if (!o->report.empty()) {
      check_output_path("--report", o->report, {".csv"});
      if (o->resume) throw InputError("--report", "needs every frame rendered; drop --resume");
    }
    const FrameRange range = parse_frame_range(o->range, o->path.frames);
    const std::unique_ptr<Style> style = resolve_style(*cmd, o->style, o->sets, o->illumination);
    (void)last_keyframe(o->path.frames, o->keyframe_every);  // validates --keyframe-every
    const bool blobs = style->info().builder == "blobs";
    const std::string& ff = o->frame_format;
    if (ff != "png" && ff != "exr" && ff != "svg" && ff != "pdf")
      throw InputError("--frame-format", "must be png, exr, svg or pdf, not '" + ff + "'");
    const bool vector = ff == "svg" || ff == "pdf";
    if (ff != "png" && !to_dir)
      throw InputError("--frame-format", "exr, svg and pdf frames need a folder output");
    if (vector) require_line_style(*style, "--style");
    check_dpi(o->dpi, "--dpi");
    if (!blobs && (o->keyframe_every != 1 || !o->keyframe_cache.empty()))
      throw InputError(o->keyframe_every != 1 ? "--keyframe-every" : "--keyframe-cache",
                       "keyframes are for the blobs style (style '" + style->info().name +
                           "' draws every frame afresh)");

    auto frame = prepare_frame(o->scene, o->view);
    SheetScene scene = sheet_scene(*frame, o->illumination, o->scene.seed);
    memoize_preprocessing(scene, o->quiet);
    const Camera base = frame->setup.camera;
    if (to_dir) {
      std::error_code ec;
      fs::create_directories(o->out, ec);
      if (ec) throw InputError("--output", "cannot create '" + o->out + "': " + ec.message());
    }
    const bool to_gif = !to_dir && fs::path(o->out).extension() == ".gif";
    std::unique_ptr<VideoOut> video;
    std::unique_ptr<GifWriter> gif;
    if (to_gif)
      gif = std::make_unique<GifWriter>(o->out, o->fps, cv::Size(base.width, base.height),
                                        o->path.frames);
    else if (!to_dir)
      video = std::make_unique<VideoOut>(o->out, o->fps, cv::Size(base.width, base.height));
    TurntableRenderer renderer(
        scene, *style, o->path, o->keyframe_every, o->keyframe_cache,
        blobs ? keyframe_signature(*frame, *style, o->path, o->keyframe_every) : "");

    std::ostringstream csv;
    csv << "frame,seconds,flicker,reprojection_error,line_pop" << (blobs ? ",jitter" : "") << "\n";
    TurntableFrame previous;
    int written = 0, skipped = 0;
    ProgressOptions po;
    po.quiet = o->quiet;
    Progress progress("turntable", static_cast<size_t>(range.end - range.begin), po);
    for (int i = range.begin; i < range.end; ++i) {
      const std::string file = (fs::path(o->out) / frame_name(i, o->frame_format)).string();
      if (o->resume && fs::exists(file)) {
        ++skipped;
        progress.step("frame " + std::to_string(i) + " kept");
        continue;
      }
      const auto t0 = std::chrono::steady_clock::now();
      TurntableFrame now = renderer.render(i, !o->report.empty(), vector);
      if (vector) {
        write_vector_drawing(file, *now.strokes, vector_page(*style, o->view, o->dpi));
      } else if (to_dir) {
        write_styled_image(file, now.image, o->dpi);
      } else if (gif) {
        gif->write(now.image);
      } else {
        cv::Mat bgr;
        cv::cvtColor(now.image, bgr, cv::COLOR_BGRA2BGR);
        video->write(bgr);
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!o->report.empty()) {
        csv << i << ',' << seconds << ',';
        if (!previous.image.empty()) {
          const FrameCoherence c = frame_coherence(previous.view, now.view);
          csv << frame_flicker(previous.image, now.image, previous.mask, now.mask) << ','
              << c.reprojection_error << ',';
          if (c.line_pop) csv << *c.line_pop;
        } else {
          csv << ",,";
        }
        if (now.blobs) {
          csv << ',';
          if (!previous.image.empty() && previous.blobs)
            csv << blob_jitter(*previous.blobs, *now.blobs);
        }
        csv << '\n';
        previous = std::move(now);
      }
      ++written;
      progress.step("frame " + std::to_string(i));
    }
    progress.finish();
    release_frame(frame);
    if (video) video->finish();
    if (gif) gif->finish();
    if (!o->report.empty()) write_file_atomic(o->report, csv.str());
    std::printf("wrote %s (%d frame(s)%s, %dx%d, style %s)\n", o->out.c_str(), written,
                skipped > 0 ? (", " + std::to_string(skipped) + " kept").c_str() : "", base.width,
                base.height, style->info().name.c_str());
  };
}

}  // namespace sylva::cli
