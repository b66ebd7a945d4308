// sylva tradeoff SCENE --study keyframes -o KF.csv [--plot KF.png] [--every LIST] [--frames N]
//   [--degrees D] [--axis y] [--zoom Z] [view options] [--style blobs] [--set ...]
// Time, flicker and outline jitter of a blobs turntable for each keyframe interval, against
// fresh blobs every frame (studies/keyframe_study.h).
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/frame.h"
#include "cli/tradeoff.h"
#include "core/progress.h"
#include "studies/keyframe_study.h"

namespace sylva::cli {

namespace {

void print_table(const KeyframeStudy& study) {
  std::printf("%6s %9s %9s %9s %9s %9s %9s %9s %9s\n", "every", "seconds", "s/frame", "keyframes",
              "flick_avg", "flick_max", "jitter_px", "err_avg", "err_max");
  for (const KeyframeStudyRow& r : study.rows)
    std::printf("%6d %9.3f %9.4f %9d %9s %9s %9s %9.3f %9.3f%s\n", r.every, r.seconds,
                r.seconds_per_frame, r.keyframes, table_cell(r.flicker_mean, "%.3f").c_str(),
                table_cell(r.flicker_max, "%.3f").c_str(),
                table_cell(r.jitter_mean, "%.3f").c_str(), r.error_mean, r.error_max,
                r.reference ? "  (reference)" : "");
}

}  // namespace

void add_keyframe_study_options(CLI::App& cmd, KeyframeStudyCliOptions& o) {
  const size_t before = cmd.get_options().size();
  cmd.add_option("--every", o.every,
                 "keyframes study: keyframe intervals n, comma-separated, each in [1, 100000]; "
                 "n = 1 (the reference) is always measured")
      ->capture_default_str();
  cmd.add_option("--frames", o.frames, "keyframes study: turntable frames, [1, 100000]")
      ->capture_default_str();
  cmd.add_option("--degrees", o.degrees,
                 "keyframes study: rotation over all frames in degrees, [-36000, 36000]")
      ->capture_default_str();
  cmd.add_option("--axis", o.axis, "keyframes study: world axis to turn about: x, y (up) or z")
      ->capture_default_str();
  cmd.add_option("--zoom", o.zoom, "keyframes study: image magnification, (0, 100]; 1 = framed")
      ->capture_default_str();
  const std::vector<CLI::Option*> all = cmd.get_options();
  o.options.assign(all.begin() + long(before), all.end());
}

void run_keyframe_study_command(const SceneOptions& scene_options, const KeyframeStudyCliOptions& o,
                                ViewOptions& view, const Style& style, const TradeoffOutputs& out) {
  // Every option is checked before the scene is loaded.
  resolve_view_options(view);
  KeyframeStudyOptions so;
  so.path.frames = o.frames;
  so.path.degrees = o.degrees;
  so.path.axis = o.axis.size() == 1 ? o.axis[0] : '?';
  so.path.zoom = o.zoom;
  so.every = parse_numbers<int>(o.every, "--every");
  validate_keyframe_study(so, style);
  validate_blob_params(style.params().blobs);

  auto frame = prepare_frame(scene_options, view);
  const SheetScene scene = sheet_scene(*frame, foliage_run({}), scene_options.seed);
  KeyframeStudy study;
  {
    ProgressOptions po;
    po.quiet = out.quiet;
    Progress progress("keyframes study", keyframe_study_frames(so), po);
    so.on_frame = [&progress](const std::string& what) { progress.step(what); };
    study = run_keyframe_study(scene, style, so);
  }
  release_frame(frame);
  const std::string name = std::filesystem::path(scene_options.path).stem().string();
  write_study_files(out, keyframe_study_csv(study),
                    [&] { return plot_keyframe_study(study, name); });

  std::printf(
      "%s: %dx%d, style %s, %d frames over %g degrees; reference: n = 1 (fresh blobs every "
      "frame); flicker, error: 8-bit levels inside the plant; jitter: px\n",
      name.c_str(), study.width, study.height, study.style.c_str(), study.path.frames,
      double(study.path.degrees));
  print_table(study);
  print_written(out, study.rows.size());
}

}  // namespace sylva::cli
