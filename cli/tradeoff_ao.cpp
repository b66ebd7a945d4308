// sylva tradeoff SCENE --study ao -o AO.csv [--plot AO.png] [--models LIST] [--shells LIST]
//   [--rays LIST] [--reference-rays N] [--repeats N] [view options] [--style S] [--set ...]
// The AO models' error against ray-traced visibility and the time they add to a frame
// (studies/ao_study.h).
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/tradeoff.h"
#include "core/progress.h"
#include "core/scene/instances.h"
#include "studies/ao_study.h"

namespace sylva::cli {

namespace {

void print_table(const AoStudy& study) {
  std::printf("%-18s %5s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n", "model", "k/ray", "alpha_rho",
              "setup_s", "frame_s", "added_s", "fol_rmse", "fol_mae", "fol_trend", "oth_rmse",
              "oth_mae", "oth_trend");
  for (const AoStudyRow& r : study.rows) {
    const std::string k = r.shells ? std::to_string(*r.shells)
                          : r.rays ? std::to_string(*r.rays)
                                   : std::string("-");
    std::printf("%-18s %5s", r.model.c_str(), k.c_str());
    if (!r.error.empty()) {
      std::printf(" failed: %s\n", r.error.c_str());
      continue;
    }
    std::printf(
        " %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s%s\n", table_cell(r.alpha_rho, "%.4g").c_str(),
        table_cell(r.setup_seconds, "%.3f").c_str(), table_cell(r.frame_seconds, "%.4f").c_str(),
        table_cell(r.added_seconds, "%.4f").c_str(), table_cell(r.foliage.rmse, "%.4f").c_str(),
        table_cell(r.foliage.mae, "%.4f").c_str(), table_cell(r.foliage.trend_rmse, "%.4f").c_str(),
        table_cell(r.nonfoliage.rmse, "%.4f").c_str(), table_cell(r.nonfoliage.mae, "%.4f").c_str(),
        table_cell(r.nonfoliage.trend_rmse, "%.4f").c_str(), r.reference ? "  (reference)" : "");
  }
}

}  // namespace

void add_ao_study_options(CLI::App& cmd, AoStudyCliOptions& o) {
  const size_t before = cmd.get_options().size();
  o.view.size = "512x512";
  add_view_options(cmd, o.view);
  const std::vector<CLI::Option*> with_view = cmd.get_options();
  o.view_options.assign(with_view.begin() + long(before), with_view.end());
  cmd.add_option("--models", o.models,
                 "ao study: the AO models measured besides none and the reference, "
                 "comma-separated (as ao.model)")
      ->capture_default_str();
  cmd.add_option("--shells", o.shells, "ao study: k of hegeman-shells, each in [1, 64]")
      ->capture_default_str();
  cmd.add_option("--rays", o.rays, "ao study: rays per pixel of raytraced, each in [1, 4096]")
      ->capture_default_str();
  cmd.add_option("--reference-rays", o.reference_rays,
                 "ao study: rays per pixel of the reference, [1, 4096]")
      ->capture_default_str();
  cmd.add_option("--repeats", o.repeats,
                 "ao study: timed frames per model (their median is reported), [1, 100]")
      ->capture_default_str();
  const std::vector<CLI::Option*> all = cmd.get_options();
  o.options.assign(all.begin() + long(before), all.end());
}

void run_ao_study_command(const SceneOptions& scene_options, AoStudyCliOptions& o,
                          const Style& style, const TradeoffOutputs& out) {
  // Every option is checked before the scene is loaded.
  resolve_view_options(o.view);
  AoStudyOptions so;
  so.models = split_list(o.models, "--models");
  so.shells = parse_numbers<int>(o.shells, "--shells");
  so.rays = parse_numbers<int>(o.rays, "--rays");
  so.reference_rays = o.reference_rays;
  so.repeats = o.repeats;
  so.alpha_rho = style.params().ao.alpha_rho;
  so.seed = scene_options.seed;
  so.luft = foliage_params(style.params().foliage, scene_options.seed);
  try {
    validate_ao_study(so);
  } catch (const InputError& e) {
    const std::string where = e.where().starts_with("ao.") ? e.where() : "--" + e.where();
    throw InputError(where, e.reason());
  }

  // The ray-traced reference and the fits see world-space triangles: an instanced scene is
  // flattened.
  Scene scene = flatten(load_scene_for_cli(scene_options));
  apply_ground_option(scene, o.view);
  so.camera = view_camera(scene, o.view);
  so.lighting = lighting_for(o.view);
  so.request = raster_request(o.view);
  const std::unique_ptr<GlContext> context = start_gl(o.view);
  so.context = context.get();
  AoStudy study;
  {
    ProgressOptions po;
    po.quiet = out.quiet;
    Progress progress("ao study", ao_study_runs(so), po);
    so.on_run = [&progress](const std::string& what) { progress.step(what); };
    study = run_ao_study(scene, so);
  }
  const std::string name = std::filesystem::path(scene_options.path).stem().string();
  write_study_files(out, ao_study_csv(study), [&] { return plot_ao_study(study, name); });

  std::printf(
      "%s: %dx%d; reference: ray-traced, %d rays per pixel (mean %.4f); frame time: median of "
      "%d\n",
      name.c_str(), study.width, study.height, study.reference_rays, study.reference_mean,
      study.repeats);
  print_table(study);
  print_written(out, study.rows.size());
}

}  // namespace sylva::cli
