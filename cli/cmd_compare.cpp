// sylva compare SCENE [--styles a,b,file.toml | --style S] [--sweep key=v1,v2]... -o SHEET.png
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/frame.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/progress.h"
#include "styles/presets.h"
#include "styles/sheet_layout.h"

namespace sylva::cli {

namespace {

struct CompareOpts {
  SceneOptions scene;
  ViewOptions view;
  FoliageRunOptions foliage;
  std::vector<std::string> styles;
  std::string style;
  std::vector<std::string> sets, sweeps;
  int columns = 0;
  int detail_lines = 3;
  std::string out, graph;
  bool quiet = false;
};

void add_compare_options(CLI::App& cmd, CompareOpts& o) {
  add_scene_options(cmd, o.scene);
  add_view_options(cmd, o.view);
  add_illumination_options(cmd, &o.foliage);
  CLI::Option* styles =
      cmd.add_option("--styles", o.styles,
                     "Comma-separated built-in styles and preset files (.toml); default: every "
                     "built-in style")
          ->delimiter(',');
  CLI::Option* style =
      cmd.add_option("--style", o.style, "One style for every cell (with --sweep)");
  styles->excludes(style);
  cmd.add_option("--set", o.sets,
                 "Override a parameter in every cell: section.key=value (repeatable)");
  cmd.add_option("--sweep", o.sweeps,
                 "A cell per value: section.key=v1,v2,... (repeatable; two sweeps make a table "
                 "with the last one across)");
  cmd.add_option("--columns", o.columns, "Cells per row, 0 = automatic")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  cmd.add_option("--label-lines", o.detail_lines,
                 "Lines of changed parameters under each title, in [0, 20]")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  cmd.add_option("--graph", o.graph, "Also write the render graph as Graphviz .dot");
  cmd.add_flag("-q,--quiet", o.quiet, "No progress output");
  cmd.add_option("-o,--output", o.out, "Output sheet (.png or .jpg)")->required();
}

// Runs the sheet's graph with progress (the frame's GL resources are released after).
void run_sheet_graph(RenderGraph& graph, const CompareOpts& o, size_t cells, const SheetPlan& plan,
                     const FoliageRun& run) {
  if (!run.surface_out.empty() && plan.foliage_passes > 1)
    throw InputError("--surface-out", "the sheet computes " + std::to_string(plan.foliage_passes) +
                                          " implicit surfaces; write one with sylva render");
  if (!o.graph.empty()) write_file_atomic(o.graph, graph.to_dot());
  if (!o.quiet)
    std::fprintf(stderr, "compare: %zu cells, %d raster pass(es), %d foliage preprocessing(s)\n",
                 cells, plan.raster_passes, plan.foliage_passes);
  ProgressOptions po;
  po.quiet = o.quiet;
  Progress progress("compare", graph.live_passes().size(), po);
  graph.execute([&](const std::string& pass) { progress.step(pass); });
}

// Each cell's image, titled by its style and swept values, with its changed parameters.
std::vector<SheetCell> sheet_cells(const RenderGraph& graph, const SheetPlan& plan,
                                   const std::vector<SheetEntry>& entries,
                                   const std::vector<std::unique_ptr<Style>>& built,
                                   const std::vector<std::string>& sweeps) {
  std::vector<SheetCell> cells;
  std::vector<std::string> swept;
  for (const std::string& s : sweeps)
    swept.push_back(s.substr(0, s.find('=')));
  for (size_t i = 0; i < entries.size(); ++i) {
    SheetCell c;
    c.image = graph.get(plan.outputs[i]);
    c.title = {built[i]->info().name};
    c.title.insert(c.title.end(), entries[i].swept.begin(), entries[i].swept.end());
    c.details = changed_parameters(*built[i], swept);
    cells.push_back(std::move(c));
  }
  return cells;
}

}  // namespace

Action add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareOpts>();
  o->view.size = "512x512";
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Render a scene in several styles (or one style over swept parameters) into one "
      "labelled contact sheet; buffers and preprocessing are shared between the cells");
  add_compare_options(*cmd, *o);
  return [o, cmd] {
    check_output_path("--output", o->out, {".png", ".jpg", ".jpeg"});
    if (!o->graph.empty()) check_output_path("--graph", o->graph, {".dot", ".gv"});
    std::vector<std::string> names = o->styles;
    if (!o->style.empty()) names = {o->style};
    if (names.empty()) names = builtin_preset_names();
    const std::vector<SheetEntry> entries = expand_sheet(names, o->sets, o->sweeps);
    const auto built = build_sheet_styles(entries, given_foliage_options(*cmd));
    const FoliageRun run = foliage_run(o->foliage, o->quiet);
    std::vector<const Style*> list;
    for (const auto& s : built)
      list.push_back(s.get());
    auto frame = prepare_frame(o->scene, o->view, result_cache_dir(o->foliage));
    RenderGraph graph;
    const SheetPlan plan = add_sheet_passes(graph, list, sheet_scene(*frame, run, o->scene.seed));
    run_sheet_graph(graph, *o, entries.size(), plan, run);
    release_frame(frame);
    SheetLayout layout;
    layout.columns = o->columns > 0 ? o->columns : sheet_columns(entries.size(), o->sweeps);
    layout.max_detail_lines = o->detail_lines;
    write_styled_image(o->out,
                       layout_sheet(sheet_cells(graph, plan, entries, built, o->sweeps), layout));
    std::printf("wrote %s (%zu cells of %dx%d)\n", o->out.c_str(), entries.size(), o->view.width,
                o->view.height);
  };
}

}  // namespace sylva::cli
