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
#include "studies/abstraction_study.h"
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
                 "coherence and abstraction studies: degrees between consecutive views, "
                 "[-360, 360], not 0")
      ->capture_default_str();
  cmd.add_option("--details", o.details,
                 "abstraction study: values of ink.detail (px at 1024 px), comma-separated, each "
                 "in [0, 64]")
      ->capture_default_str();
  const std::vector<CLI::Option*> all = cmd.get_options();
  o.options.assign(all.begin() + long(before), all.end());
}

namespace {

// The studies' views: `frames` views --step degrees apart about --axis, at --zoom (checked).
CoherenceStudyOptions views_of(const CoherenceStudyCliOptions& o,
                               const KeyframeStudyCliOptions& path, int frames) {
  CoherenceStudyOptions so;
  so.frames = frames;
  so.step = o.step;
  so.axis = path.axis.size() == 1 ? path.axis[0] : '?';
  so.zoom = path.zoom;
  validate_coherence_study(so);
  return so;
}

}  // namespace

void run_coherence_study_command(const SceneOptions& scene_options,
                                 const CoherenceStudyCliOptions& o,
                                 const KeyframeStudyCliOptions& path, bool frames_given,
                                 ViewOptions& view, const std::vector<ParamAssignment>& foliage,
                                 const std::vector<std::string>& sets, const TradeoffOutputs& out) {
  // Every option is checked before the scene is loaded.
  resolve_view_options(view);
  CoherenceStudyOptions so = views_of(o, path, frames_given ? path.frames : 12);
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

namespace {

void print_table(const AbstractionStudy& study) {
  std::printf("%-10s %6s %6s %6s %7s %7s %9s %8s %9s\n", "style", "detail", "wood", "tone",
              "inside", "marks", "overreach", "pop_avg%", "s/frame");
  for (const AbstractionStudyRow& r : study.rows) {
    const std::optional<double> pop =
        r.line_pop_mean ? std::optional<double>(100.0 * *r.line_pop_mean) : std::nullopt;
    std::printf("%-10s %6g %6.3f %6.3f %7.3f %7.2f %9.3f %8s %9.4f\n", r.style.c_str(),
                double(r.detail), r.depiction.wood, r.depiction.tone, r.depiction.inside,
                r.depiction.marks, r.depiction.overreach, table_cell(pop, "%.2f").c_str(),
                r.seconds_per_frame);
  }
}

}  // namespace

void run_abstraction_study_command(const SceneOptions& scene_options,
                                   const CoherenceStudyCliOptions& o,
                                   const KeyframeStudyCliOptions& path, bool frames_given,
                                   ViewOptions& view, const std::vector<ParamAssignment>& foliage,
                                   const std::vector<std::string>& sets,
                                   const TradeoffOutputs& out) {
  resolve_view_options(view);
  CoherenceStudyOptions so = views_of(o, path, frames_given ? path.frames : 5);
  const std::vector<float> details = parse_numbers<float>(o.details, "--details");
  for (float d : details)
    if (!(d >= 0.0f && d <= 64.0f))
      throw InputError("--details", "each value must be in [0, 64] px, not " + std::to_string(d));
  const std::vector<std::string> names =
      split_list(o.styles.empty() ? "ink,pen" : o.styles, "--styles");
  const auto built =
      build_sheet_styles(expand_sheet(names, sets, {"ink.detail=" + o.details}), foliage);
  const auto references =
      build_sheet_styles(expand_sheet({"standard", "expressive"}, sets, {}), foliage);
  std::vector<AbstractionCell> cells;
  for (size_t i = 0; i < built.size(); ++i)
    cells.push_back({built[i].get(), names[i / details.size()], details[i % details.size()]});

  auto frame = prepare_frame(scene_options, view);
  const SheetScene scene = sheet_scene(*frame, foliage_run({}), scene_options.seed);
  AbstractionStudy study;
  {
    ProgressOptions po;
    po.quiet = out.quiet;
    Progress progress("abstraction study", cells.size(), po);
    so.on_frame = nullptr;
    study = run_abstraction_study(scene, cells, *references[0], *references[1], so);
    progress.step("done");
  }
  release_frame(frame);
  const std::string name = std::filesystem::path(scene_options.path).stem().string();
  write_study_files(out, abstraction_study_csv(study),
                    [&] { return plot_abstraction_study(study, name); });
  std::printf(
      "%s: %dx%d; depiction measures of the first view (../shared/tools/depiction.py's); pop over "
      "%d views %g degrees apart\n",
      name.c_str(), study.width, study.height, so.frames, double(so.step));
  print_table(study);
  print_written(out, study.rows.size());
}

}  // namespace sylva::cli
