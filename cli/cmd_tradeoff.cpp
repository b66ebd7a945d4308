// sylva tradeoff SCENE --study foliage -o STUDY.csv [--plot STUDY.png] [--fractions LIST]
//   [--grids LIST] [--normal-sources LIST] [--encodings LIST] [--reference-grid N] [--quiet]
//   [scene options] [--rho --tau --ka-min --d-min --exponent --blend --smooth --decimate
//   --per-triangle]
// sylva tradeoff SCENE --study ao ... (cli/tradeoff_ao.cpp)
// sylva tradeoff SCENE --study keyframes ... (cli/tradeoff_keyframes.cpp)
// Measures a speed/accuracy trade against a reference the program computes itself
// (DESIGN.md §5): the Luft et al. foliage preprocessing (studies/foliage_study.h), the
// ambient-occlusion models (studies/ao_study.h) or the keyframe interval of blob turntables
// (studies/keyframe_study.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/frame.h"
#include "cli/illumination_options.h"
#include "cli/tradeoff.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/image_io.h"
#include "core/progress.h"
#include "core/scene/instances.h"
#include "studies/foliage_study.h"

namespace sylva::cli {

std::vector<std::string> split_list(const std::string& text, const std::string& where) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    out.push_back(item);
  if (!text.empty() && text.back() == ',') out.emplace_back();
  for (const std::string& item : out)
    if (item.empty())
      throw InputError(where, "expected a comma-separated list, got '" + text + "'");
  if (out.empty()) throw InputError(where, "name at least one value");
  return out;
}

std::string table_cell(const std::optional<double>& v, const char* fmt) {
  if (!v) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, *v);
  return buf;
}

void write_study_files(const TradeoffOutputs& out, const std::string& csv,
                       const std::function<cv::Mat()>& plot) {
  cv::Mat picture;
  if (!out.plot.empty()) picture = plot();
  write_file_atomic(out.csv, csv);
  if (!out.plot.empty()) write_image(out.plot, picture);
}

void print_written(const TradeoffOutputs& out, size_t rows) {
  std::printf("wrote %s (%zu rows)%s%s\n", out.csv.c_str(), rows, out.plot.empty() ? "" : " and ",
              out.plot.c_str());
}

namespace {

// The studies `--study` accepts.
const char* const kStudies = "foliage, ao, keyframes, coherence, abstraction";

// An option of one study given to another: one clear line instead of silently ignoring it.
void reject_options(const std::vector<CLI::Option*>& options, const std::string& study) {
  for (const CLI::Option* opt : options)
    if (opt->count() > 0) throw InputError(opt->get_name(), "does not apply to --study " + study);
}

std::vector<NormalSource> parse_normal_sources(const std::string& text) {
  std::vector<NormalSource> out;
  for (const std::string& n : split_list(text, "--normal-sources")) {
    if (n == "surface")
      out.push_back(NormalSource::Surface);
    else if (n == "gradient")
      out.push_back(NormalSource::Gradient);
    else
      throw InputError("--normal-sources",
                       "unknown value '" + n + "' (allowed: surface, gradient)");
  }
  return out;
}

std::vector<KaEncoding> parse_encodings(const std::string& text) {
  std::vector<KaEncoding> out;
  for (const std::string& n : split_list(text, "--encodings")) {
    if (n == "length")
      out.push_back(KaEncoding::Length);
    else if (n == "attribute")
      out.push_back(KaEncoding::Attribute);
    else
      throw InputError("--encodings", "unknown value '" + n + "' (allowed: length, attribute)");
  }
  return out;
}

// One line per preprocessing run; the encodings' interior ka errors side by side.
void print_table(const FoliageStudy& study, const std::vector<KaEncoding>& encodings) {
  std::printf("%-8s %5s %-8s %10s %9s %9s %9s %9s", "fraction", "grid", "normals", "generators",
              "seconds", "mean_deg", "p95_deg", "ka_rmse");
  for (KaEncoding e : encodings)
    std::printf(" %*s", e == KaEncoding::Length ? 13 : 16,
                (std::string("ka_int_") + ka_encoding_name(e)).c_str());
  std::printf("\n");
  for (size_t i = 0; i < study.rows.size(); i += encodings.size()) {
    const FoliageStudyRow& r = study.rows[i];
    std::printf("%-8g %5d %-8s", r.fraction, r.grid, normal_source_name(r.normals));
    if (!r.error.empty()) {
      std::printf(" failed: %s\n", r.error.c_str());
      continue;
    }
    std::printf(
        " %10zu %9s %9s %9s %9s", r.generators.value_or(0), table_cell(r.seconds, "%.3f").c_str(),
        table_cell(r.normal_mean_deg, "%.3f").c_str(), table_cell(r.normal_p95_deg, "%.3f").c_str(),
        table_cell(r.ka_rmse, "%.5f").c_str());
    for (size_t e = 0; e < encodings.size(); ++e)
      std::printf(" %*s", encodings[e] == KaEncoding::Length ? 13 : 16,
                  table_cell(study.rows[i + e].ka_interior_rmse, "%.5f").c_str());
    std::printf("%s\n", r.reference ? "  (reference)" : "");
  }
}

struct TradeoffOpts {
  SceneOptions scene;
  std::string study, out, plot;
  std::string fractions = "1,0.5,0.25,0.1,0.05,0.01";
  std::string grids = "32,64,128,256";
  std::string normal_sources = "surface,gradient";
  std::string encodings = "length,attribute";
  int reference_grid = 256;
  std::string thresholds = "scaled";
  std::string style = "standard";
  std::vector<std::string> sets;
  bool quiet = false;
  AoStudyCliOptions ao;
  KeyframeStudyCliOptions keyframes;
  CoherenceStudyCliOptions coherence;
  std::vector<CLI::Option*> foliage_only;
};

// The foliage study's sweep: --fractions, --grids, --normal-sources, --encodings,
// --reference-grid and --thresholds (remembered in foliage_only, which other studies reject).
void add_foliage_sweep_options(CLI::App& cmd, TradeoffOpts& o) {
  const size_t before = cmd.get_options().size();
  cmd.add_option("--fractions", o.fractions,
                 "Shares of leaves used as generators, comma-separated, each in (0, 1]")
      ->capture_default_str();
  cmd.add_option("--grids", o.grids,
                 "Marching-cubes cells along the longest axis, comma-separated, each in [2, "
                 "1024]")
      ->capture_default_str();
  cmd.add_option("--normal-sources", o.normal_sources, "surface and/or gradient")
      ->capture_default_str();
  cmd.add_option("--encodings", o.encodings, "length and/or attribute (ka encodings)")
      ->capture_default_str();
  cmd.add_option("--reference-grid", o.reference_grid,
                 "The reference's grid, [2, 1024]; raised to the largest of --grids")
      ->capture_default_str();
  cmd.add_option("--thresholds", o.thresholds,
                 "tau and d-min of a run with fewer generators: scaled (the reference's times "
                 "the share of generators, matching the expected density) or fixed (the "
                 "reference's)")
      ->capture_default_str();
  const std::vector<CLI::Option*> all = cmd.get_options();
  o.foliage_only.assign(all.begin() + long(before), all.end());
}

// The AO study's options but its view options are rejected by the studies that take a view only.
void reject_ao_options_but_view(const TradeoffOpts& o) {
  for (CLI::Option* opt : o.ao.options)
    if (std::find(o.ao.view_options.begin(), o.ao.view_options.end(), opt) ==
        o.ao.view_options.end())
      reject_options({opt}, o.study);
}

void run_coherence(CLI::App& cmd, TradeoffOpts& o) {
  reject_options(o.foliage_only, o.study);
  reject_ao_options_but_view(o);
  for (const char* name : {"--every", "--degrees", "--style"})
    reject_options({cmd.get_option(name)}, o.study + " (use --styles and --step)");
  const bool frames = cmd.get_option("--frames")->count() > 0;
  if (o.study == "abstraction")
    return run_abstraction_study_command(o.scene, o.coherence, o.keyframes, frames, o.ao.view,
                                         given_foliage_options(cmd), o.sets,
                                         {o.out, o.plot, o.quiet});
  reject_options({cmd.get_option("--details")}, o.study);
  run_coherence_study_command(o.scene, o.coherence, o.keyframes, frames, o.ao.view,
                              given_foliage_options(cmd), o.sets, {o.out, o.plot, o.quiet});
}

void run_keyframes(const CLI::App& cmd, TradeoffOpts& o) {
  reject_options(o.foliage_only, o.study);
  reject_ao_options_but_view(o);
  // A blobs style unless --style names another (which is then rejected).
  if (cmd.get_option("--style")->count() == 0) o.style = "blobs";
  const std::unique_ptr<Style> style = resolve_style(cmd, o.style, o.sets);
  run_keyframe_study_command(o.scene, o.keyframes, o.ao.view, *style, {o.out, o.plot, o.quiet});
}

// Every option of the foliage study, checked before the scene is loaded.
FoliageStudyOptions foliage_study_options(const CLI::App& cmd, const TradeoffOpts& o) {
  FoliageStudyOptions so;
  so.base = foliage_params(resolve_style(cmd, o.style, o.sets)->params().foliage, o.scene.seed);
  so.fractions = parse_numbers<double>(o.fractions, "--fractions");
  so.grids = parse_numbers<int>(o.grids, "--grids");
  so.normals = parse_normal_sources(o.normal_sources);
  so.encodings = parse_encodings(o.encodings);
  so.reference_grid = o.reference_grid;
  if (o.thresholds != "scaled" && o.thresholds != "fixed")
    throw InputError("--thresholds",
                     "unknown value '" + o.thresholds + "' (allowed: scaled, fixed)");
  so.scale_thresholds = o.thresholds == "scaled";
  try {
    validate_foliage_study(so);
  } catch (const InputError& e) {
    throw InputError("--" + e.where(), e.reason());
  }
  return so;
}

void run_foliage(const CLI::App& cmd, const TradeoffOpts& o) {
  FoliageStudyOptions so = foliage_study_options(cmd, o);
  // The study times one preprocessing of the whole scene: an instanced one is flattened.
  const Scene scene = flatten(load_scene_for_cli(o.scene));
  FoliageStudy study;
  {
    ProgressOptions po;
    po.quiet = o.quiet;
    Progress progress("foliage study", foliage_study_runs(so), po);
    so.on_run = [&progress](const std::string& what) { progress.step(what); };
    study = run_foliage_study(scene, so);
  }
  const std::string name = std::filesystem::path(o.scene.path).stem().string();
  const TradeoffOutputs outputs{o.out, o.plot, o.quiet};
  write_study_files(outputs, foliage_study_csv(study),
                    [&] { return plot_foliage_study(study, name); });
  std::printf("%s: %zu leaves; reference %.2f s (rho %.4g, tau %.4g, d_min %.4g)\n", name.c_str(),
              study.reference.leaves, study.reference_seconds, study.reference.rho,
              study.reference.tau, study.reference.d_min);
  print_table(study, so.encodings);
  print_written(outputs, study.rows.size());
}

// Checks the study and outputs, then runs the study with the options it takes (the others'
// are rejected).
void run_tradeoff(CLI::App& cmd, TradeoffOpts& o) {
  if (o.study != "foliage" && o.study != "ao" && o.study != "keyframes" && o.study != "coherence" &&
      o.study != "abstraction")
    throw InputError("--study", "unknown study '" + o.study + "' (allowed: " + kStudies + ")");
  check_output_path("--output", o.out, {".csv"});
  if (!o.plot.empty()) check_output_path("--plot", o.plot, {".png"});
  if (o.study != "coherence" && o.study != "abstraction")
    reject_options(o.coherence.options, o.study);
  if (o.study == "coherence" || o.study == "abstraction") return run_coherence(cmd, o);
  if (o.study == "keyframes") return run_keyframes(cmd, o);
  reject_options(o.keyframes.options, o.study);
  if (o.study == "ao") {
    reject_options(o.foliage_only, o.study);
    const std::unique_ptr<Style> style = resolve_style(cmd, o.style, o.sets);
    run_ao_study_command(o.scene, o.ao, *style, {o.out, o.plot, o.quiet});
    return;
  }
  reject_options(o.ao.options, o.study);
  run_foliage(cmd, o);
}

}  // namespace

Action add_tradeoff_command(CLI::App& app) {
  auto o = std::make_shared<TradeoffOpts>();
  CLI::App* cmd = app.add_subcommand(
      "tradeoff",
      "Measure speed against accuracy over a parameter sweep, against a reference the "
      "program computes (CSV and a plot)");
  add_scene_options(*cmd, o->scene);
  // The Luft options that stay fixed over the sweep; fraction, grid, normal source and
  // encoding are the sweep's own lists below, and every run is computed, never cached.
  add_illumination_options(
      *cmd, nullptr,
      {"foliage.fraction", "foliage.grid", "foliage.normal_source", "foliage.ka_encoding"});
  cmd->add_option("--study", o->study, std::string("What to study: ") + kStudies)->required();
  cmd->add_option("-o,--output", o->out, "Output table (.csv)")->required();
  cmd->add_option("--plot", o->plot, "Also draw error against time (.png)");
  add_foliage_sweep_options(*cmd, *o);
  add_ao_study_options(*cmd, o->ao);
  add_keyframe_study_options(*cmd, o->keyframes);
  add_coherence_study_options(*cmd, o->coherence);
  // The settings the sweep starts from: a style's foliage.* keys (after --set), then the
  // explicit options above.
  add_style_options(*cmd, o->style, o->sets);
  cmd->add_flag("-q,--quiet", o->quiet, "No progress bar");
  return [o, cmd] { run_tradeoff(*cmd, *o); };
}

}  // namespace sylva::cli
