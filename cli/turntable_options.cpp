#include "cli/turntable_options.h"

#include <filesystem>

#include "cli/commands.h"
#include "cli/frame.h"
#include "core/error.h"
#include "core/io/svg_writer.h"
#include "npr/blob_keyframes.h"

namespace fs = std::filesystem;

namespace sylva::cli {

namespace {

void add_path_options(CLI::App& cmd, TurntableOptions& o) {
  cmd.add_option("--frames", o.path.frames, "Number of frames, [1, 100000]")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--degrees", o.path.degrees,
                 "Rotation over all frames in degrees, [-36000, 36000]; 360 loops seamlessly")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--axis", o.axis, "World axis to turn about: x, y (up) or z")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--zoom", o.path.zoom, "Image magnification, (0, 100]; 1 = framed")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--fps", o.fps,
                 "Frames per second of the MP4 or GIF, [1, 240] (a GIF stores whole hundredths of "
                 "a second)")
      ->capture_default_str()
      ->group(kTurntableGroup);
}

void add_slice_options(CLI::App& cmd, TurntableOptions& o) {
  cmd.add_option("--frame-range", o.range,
                 "Render frames A to B-1 only (A:B, 0-based; folder output), e.g. for a "
                 "render farm; the frames equal those of a full run")
      ->group(kTurntableGroup);
  cmd.add_flag("--resume", o.resume,
               "Keep the complete frames already in the output folder (a damaged or partial "
               "frame, or a killed run's temporary file, is rendered again)")
      ->group(kTurntableGroup);
  cmd.add_option("--keyframe-every", o.keyframe_every,
                 "blobs style: shrink-wrap the blobs every n-th frame and interpolate the "
                 "frames between (Dudley §5.1); >= 1, 1 = every frame")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--keyframe-cache", o.keyframe_cache,
                 "blobs style: keep the keyframes' blobs in this folder and reuse them (e.g. "
                 "across the jobs of a --frame-range split)")
      ->group(kTurntableGroup);
  cmd.add_flag("--keyframes-only", o.keyframes_only,
               "blobs style with --keyframe-cache: only fill the cache with the keyframes the "
               "--frame-range owns (a farm's first step); no frame is written")
      ->group(kTurntableGroup);
}

void add_output_options(CLI::App& cmd, TurntableOptions& o) {
  cmd.add_option("--report", o.report,
                 "Write per frame to a .csv its seconds and its coherence with the previous one: "
                 "flicker, reprojection_error, line_pop (line styles), jitter (blobs)")
      ->group(kTurntableGroup);
  cmd.add_option("--frame-format", o.frame_format,
                 "Folder output: png, exr (linear half RGBA, premultiplied, for compositing), or "
                 "svg / pdf (the strokes of a line style: ink, pen) for plotters and motion work")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_option("--dpi", o.dpi,
                 "Folder frames: pixels per inch (svg/pdf page size, png pHYs, exr xDensity), "
                 "[0, 10000]")
      ->capture_default_str()
      ->group(kTurntableGroup);
  cmd.add_flag("-q,--quiet", o.quiet, "No progress output")->group(kTurntableGroup);
  cmd.add_option("-o,--output", o.out,
                 "Output .mp4, .gif, or a folder for frames frame-00000.png, ... (or .exr/.svg/"
                 ".pdf with --frame-format; a name without extension)")
      ->required()
      ->group(kTurntableGroup);
}

// Whether `out` names a frame folder ("out/", an existing folder, a name without extension);
// checks the output's parent folder or extension.
bool check_output(const TurntableOptions& o) {
  const bool to_dir =
      o.out.ends_with("/") || fs::is_directory(o.out) || fs::path(o.out).extension().empty();
  if (!to_dir) {
    check_output_path("--output", o.out, {".mp4", ".gif"});
    if (!o.range.empty())
      throw InputError("--frame-range", "needs a folder output (an MP4 or GIF is written whole)");
    if (o.resume) throw InputError("--resume", "needs a folder output");
    return false;
  }
  fs::path dir = fs::path(o.out).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/" -> "out"
  const fs::path parent = dir.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec) && !parent.empty() && !fs::is_directory(parent, ec))
    throw InputError("--output", "parent folder of '" + o.out + "' does not exist");
  return true;
}

void check_frame_format(const TurntableOptions& o, const TurntableChecks& c) {
  if (c.frame_format != FrameFormat::Png && !c.to_dir)
    throw InputError("--frame-format", "exr, svg and pdf frames need a folder output");
  if (c.vector) require_line_style(*c.style, "--style");
  check_dpi(o.dpi, "--dpi");
}

void check_keyframe_options(const TurntableOptions& o, const TurntableChecks& c) {
  (void)last_keyframe(o.path.frames, o.keyframe_every);  // validates --keyframe-every
  if (!c.blobs && (o.keyframe_every != 1 || !o.keyframe_cache.empty() || o.keyframes_only))
    throw InputError(o.keyframe_every != 1 ? "--keyframe-every"
                     : o.keyframes_only    ? "--keyframes-only"
                                           : "--keyframe-cache",
                     "keyframes are for the blobs style (style '" + c.style->info().name +
                         "' draws every frame afresh)");
  if (o.keyframes_only && o.keyframe_cache.empty())
    throw InputError("--keyframes-only", "needs --keyframe-cache (where the keyframes go)");
  if (o.keyframes_only && !o.report.empty())
    throw InputError("--report", "--keyframes-only renders no frame to report on");
}

}  // namespace

void add_turntable_options(CLI::App& cmd, TurntableOptions& o) {
  add_scene_options(cmd, o.scene);
  add_view_options(cmd, o.view);
  add_illumination_options(cmd, &o.foliage);
  add_style_options(cmd, o.style, o.sets);
  add_path_options(cmd, o);
  add_slice_options(cmd, o);
  add_output_options(cmd, o);
}

TurntableChecks check_turntable_options(const CLI::App& cmd, TurntableOptions& o) {
  o.path.axis = o.axis.size() == 1 ? o.axis[0] : '?';
  validate_turntable(o.path);
  if (!(o.fps >= 1 && o.fps <= 240)) throw InputError("--fps", "must be in [1, 240]");
  TurntableChecks c;
  c.to_dir = check_output(o);
  if (!o.report.empty()) {
    check_output_path("--report", o.report, {".csv"});
    if (o.resume) throw InputError("--report", "needs every frame rendered; drop --resume");
  }
  c.range = parse_frame_range(o.range, o.path.frames);
  c.style = resolve_style(cmd, o.style, o.sets);
  c.blobs = c.style->traits().blob_outlines;
  c.frame_format = parse_frame_format(o.frame_format, "--frame-format");
  c.vector = is_vector_format(c.frame_format);
  check_frame_format(o, c);
  check_keyframe_options(o, c);
  return c;
}

}  // namespace sylva::cli
