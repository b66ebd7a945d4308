// sylva tradeoff SCENE --study coherence -o C.csv [--plot C.png] [--styles a,b,...]
//   [--frames N] [--step DEG] [--axis y] [--zoom Z] [view options] [--set ...]
// Reprojection error and line pop of each style over views a few degrees apart, against the
// time per frame (studies/coherence_study.h).
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/frame.h"
#include "cli/illumination_options.h"
#include "cli/tradeoff.h"
#include "core/progress.h"
#include "studies/coherence_study.h"
#include "styles/presets.h"

namespace sylva::cli {

namespace {

void print_table(const CoherenceStudy& study) {
  std::printf("%-12s %9s %10s %10s %9s %9s %9s\n", "style", "s/frame", "reproj_avg", "reproj_max",
              "pop_avg%", "pop_max%", "flicker");
  auto percent = [](const std::optional<double>& v) {
    return v ? std::optional<double>(100.0 * *v) : std::nullopt;
  };
  for (const CoherenceStudyRow& r : study.rows)
    std::printf("%-12s %9.4f %10.3f %10.3f %9s %9s %9.3f\n", r.style.c_str(), r.seconds_per_frame,
                r.reprojection_mean, r.reprojection_max,
                table_cell(percent(r.line_pop_mean), "%.2f").c_str(),
                table_cell(percent(r.line_pop_max), "%.2f").c_str(), r.flicker_mean);
}

}  // namespace

void add_coherence_study_options(CLI::App& cmd, CoherenceStudyCliOptions& o) {
  const size_t before = cmd.get_options().size();
  cmd.add_option("--styles", o.styles,
                 "coherence study: styles (built-in names or .toml paths), comma-separated; "
                 "default every built-in style");
  cmd.add_option("--step", o.step,
                 "coherence study: degrees between consecutive views, [-360, 360], not 0")
      ->capture_default_str();
  const std::vector<CLI::Option*> all = cmd.get_options();
  o.options.assign(all.begin() + long(before), all.end());
}

void run_coherence_study_command(const SceneOptions& scene_options,
                                 const CoherenceStudyCliOptions& o,
                                 const KeyframeStudyCliOptions& path, bool frames_given,
                                 ViewOptions& view, const std::vector<ParamAssignment>& foliage,
                                 const std::vector<std::string>& sets, const TradeoffOutputs& out) {
  // Every option is checked before the scene is loaded.
  resolve_view_options(view);
  CoherenceStudyOptions so;
  so.frames = frames_given ? path.frames : 12;
  so.step = o.step;
  so.axis = path.axis.size() == 1 ? path.axis[0] : '?';
  so.zoom = path.zoom;
  validate_coherence_study(so);
  const std::vector<std::string> names =
      o.styles.empty() ? builtin_preset_names() : split_list(o.styles, "--styles");
  const auto built = build_sheet_styles(expand_sheet(names, sets, {}), foliage);
  std::vector<const Style*> styles;
  for (const auto& s : built)
    styles.push_back(s.get());

  auto frame = prepare_frame(scene_options, view);
  const SheetScene scene = sheet_scene(*frame, foliage_run({}), scene_options.seed);
  CoherenceStudy study;
  {
    ProgressOptions po;
    po.quiet = out.quiet;
    Progress progress("coherence study", styles.size() * size_t(so.frames), po);
    so.on_frame = [&progress](const std::string& what) { progress.step(what); };
    study = run_coherence_study(scene, styles, so);
  }
  release_frame(frame);
  const std::string name = std::filesystem::path(scene_options.path).stem().string();
  write_study_files(out, coherence_study_csv(study),
                    [&] { return plot_coherence_study(study, name); });
  std::printf(
      "%s: %dx%d, %d views %g degrees apart; reprojection error: 8-bit levels with the motion "
      "taken out; pop: %% of line pixels with no line within 1.5 px of their place in the "
      "other view; flicker: plain change between views\n",
      name.c_str(), study.width, study.height, so.frames, double(so.step));
  print_table(study);
  print_written(out, study.rows.size());
}

}  // namespace sylva::cli
