#include "cli/illumination_options.h"

#include <cstdio>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/param_options.h"
#include "core/cache/result_cache.h"

namespace sylva::cli {

void add_illumination_options(CLI::App& cmd, FoliageRunOptions* run,
                              const std::vector<std::string>& skip) {
  add_param_options(cmd, foliage_param_specs(), kFoliageGroup, skip);
  if (run == nullptr) return;
  cmd.add_option("--surface-out", run->surface_out,
                 "Also write the implicit surface (.glb; a scene of many plants: each plant's "
                 "surface, placed by its instances)")
      ->group(kFoliageGroup);
  cmd.add_flag("--no-cache", run->no_cache,
               "Recompute the preprocessing; do not read or write the cache")
      ->group(kFoliageGroup);
  cmd.add_option("--cache-dir", run->cache_dir,
                 "Result cache folder (default $SYLVA_CACHE_DIR, else $XDG_CACHE_HOME/sylva, else "
                 "~/.cache/sylva)")
      ->group(kFoliageGroup);
}

std::vector<ParamAssignment> given_foliage_options(const CLI::App& cmd) {
  return given_param_options(cmd, foliage_param_specs());
}

void apply_foliage_options(const CLI::App& cmd, ParamSet& set) {
  for (const ParamAssignment& a : given_foliage_options(cmd))
    set.set(a);
}

FoliageRun foliage_run(const FoliageRunOptions& o, bool quiet) {
  FoliageRun run;
  if (!o.surface_out.empty()) check_output_path("--surface-out", o.surface_out, {".glb"});
  run.surface_out = o.surface_out;
  run.cache_dir = result_cache_dir(o);
  if (!quiet)
    run.on_done = [](const FoliageStats& st) {
      std::fprintf(stderr, "foliage illumination: %s\n", describe(st).c_str());
    };
  return run;
}

std::string result_cache_dir(const FoliageRunOptions& o) {
  if (o.no_cache) return "";
  return o.cache_dir.empty() ? default_cache_dir() : o.cache_dir;
}

}  // namespace sylva::cli
