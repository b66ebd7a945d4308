// Options of the Luft preprocessing (render, buffers, compare, turntable, bake, tradeoff): the
// foliage.* keys as CLI aliases made from their specs (--rho for `--set foliage.rho=...`,
// npr/foliage_settings.h), and what a run writes and caches: --surface-out, --no-cache,
// --cache-dir.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/params.h"
#include "npr/illumination_pass.h"

namespace sylva::cli {

struct FoliageRunOptions {
  std::string surface_out;
  bool no_cache = false;
  std::string cache_dir;  // empty = default_cache_dir()
};

// Adds the aliases of the foliage.* keys but those in `skip` (group kFoliageGroup), and, with
// `run`, --surface-out, --no-cache and --cache-dir.
void add_illumination_options(CLI::App& cmd, FoliageRunOptions* run,
                              const std::vector<std::string>& skip = {});

// The foliage aliases given on `cmd`, as assignments naming the option ("--rho").
std::vector<ParamAssignment> given_foliage_options(const CLI::App& cmd);
// Applies them to `set` (after its preset and --set: they win); errors name the option.
void apply_foliage_options(const CLI::App& cmd, ParamSet& set);

// The run's outputs: the cache folder (none with --no-cache), --surface-out (checked now) and a
// one-line report of each preprocessing on stderr unless `quiet`.
FoliageRun foliage_run(const FoliageRunOptions& o, bool quiet = false);

// The result cache folder of --cache-dir / --no-cache: "" with --no-cache, else --cache-dir,
// else default_cache_dir().
std::string result_cache_dir(const FoliageRunOptions& o);

}  // namespace sylva::cli
