// What the studies of `sylva tradeoff` share (cli/cmd_tradeoff.cpp): list parsing, the
// ambient-occlusion study's options and run (cli/tradeoff_ao.cpp; studies/ao_study.h) and the
// keyframes study's (cli/tradeoff_keyframes.cpp; studies/keyframe_study.h).
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/common_options.h"
#include "cli/illumination_options.h"
#include "core/error.h"
#include "styles/style.h"

namespace sylva::cli {

// "a,b,c" -> {"a", "b", "c"}. Throws InputError(where, ...) for an empty list or item.
std::vector<std::string> split_list(const std::string& text, const std::string& where);

// A comma-separated list of numbers. Throws InputError(where, ...) for an item that is not one.
template <typename T>
std::vector<T> parse_numbers(const std::string& text, const std::string& where) {
  std::vector<T> out;
  for (const std::string& item : split_list(text, where)) {
    T v{};
    const char* end = item.data() + item.size();
    auto [p, ec] = std::from_chars(item.data(), end, v);
    if (ec != std::errc() || p != end)
      throw InputError(where, "'" + item + "' is not a number (in '" + text + "')");
    out.push_back(v);
  }
  return out;
}

struct TradeoffOutputs {
  std::string csv, plot;  // plot empty = none
  bool quiet = false;
};

// A table cell: `v` printed with the printf format `fmt`, or "-" when there is no value.
std::string table_cell(const std::optional<double>& v, const char* fmt);

// Writes the study's CSV and, when out.plot is set, the picture `plot()` draws (each file
// atomically; the plot is drawn before either file is written).
void write_study_files(const TradeoffOutputs& out, const std::string& csv,
                       const std::function<cv::Mat()>& plot);

// "wrote OUT.csv (N rows) and OUT.png" on stdout.
void print_written(const TradeoffOutputs& out, size_t rows);

// The options only `--study ao` reads.
struct AoStudyCliOptions {
  ViewOptions view;  // the frame (size default 512x512)
  std::string models =
      "none,constant,luft-density,hegeman-sphere,hegeman-ellipsoid,hegeman-shells,raytraced";
  std::string shells = "1,2,4,8";
  std::string rays = "4,16,64";
  int reference_rays = 256;
  int repeats = 3;
  std::vector<CLI::Option*> options;       // every option above, to reject them in other studies
  std::vector<CLI::Option*> view_options;  // those of `view` (the keyframes study reads them too)
};

// Registers the view options and --models, --shells, --rays, --reference-rays, --repeats.
void add_ao_study_options(CLI::App& cmd, AoStudyCliOptions& o);

// `sylva tradeoff SCENE --study ao`: parses and checks every option, loads the scene, runs
// the study (progress on stderr), writes the CSV (and the plot) atomically and prints the
// table. `style` supplies ao.alpha_rho and the Luft preprocessing of luft-density (foliage.*).
void run_ao_study_command(const SceneOptions& scene, AoStudyCliOptions& o, const Style& style,
                          const TradeoffOutputs& out);

// The options only `--study keyframes` reads (besides the view options of AoStudyCliOptions).
struct KeyframeStudyCliOptions {
  std::string every = "1,2,5,10,20";
  int frames = 60;
  float degrees = 360.0f;
  std::string axis = "y";
  float zoom = 1.0f;
  std::vector<CLI::Option*> options;  // every option above, to reject them in other studies
};

// Registers --every, --frames, --degrees, --axis, --zoom.
void add_keyframe_study_options(CLI::App& cmd, KeyframeStudyCliOptions& o);

// `sylva tradeoff SCENE --study keyframes`: parses and checks every option (the style must
// be a blobs style), loads the scene, renders the turntable once per interval (progress on
// stderr), writes the CSV (and the plot) atomically and prints the table.
void run_keyframe_study_command(const SceneOptions& scene, const KeyframeStudyCliOptions& o,
                                ViewOptions& view, const Style& style, const TradeoffOutputs& out);

// The options only `--study coherence` reads (besides the view options, and --frames, --axis
// and --zoom of the keyframes study's).
struct CoherenceStudyCliOptions {
  std::string styles;  // empty = every built-in style (abstraction: ink,pen)
  float step = 1.0f;
  std::string details = "4,6,8,10,14,20";  // --study abstraction: the values of ink.detail
  std::vector<CLI::Option*> options;       // every option above, to reject them in other studies
};

// Registers --styles, --step and --details.
void add_coherence_study_options(CLI::App& cmd, CoherenceStudyCliOptions& o);

// `sylva tradeoff SCENE --study coherence`: every style of --styles on --frames views --step
// degrees apart (studies/coherence_study.h), CSV (and plot) written atomically, table printed.
// `frames` is the keyframes study's --frames when given, else 12; `foliage` (the foliage
// options given) and `sets` apply to every style.
void run_coherence_study_command(const SceneOptions& scene, const CoherenceStudyCliOptions& o,
                                 const KeyframeStudyCliOptions& path, bool frames_given,
                                 ViewOptions& view, const std::vector<ParamAssignment>& foliage,
                                 const std::vector<std::string>& sets, const TradeoffOutputs& out);

// `sylva tradeoff SCENE --study abstraction`: every style of --styles (default ink,pen) at each
// value of --details for ink.detail: the depiction measures of its first view, its line pop over
// --frames views (default 5) --step degrees apart and its time per frame
// (studies/abstraction_study.h); CSV (and plot) written atomically, table printed.
void run_abstraction_study_command(const SceneOptions& scene, const CoherenceStudyCliOptions& o,
                                   const KeyframeStudyCliOptions& path, bool frames_given,
                                   ViewOptions& view, const std::vector<ParamAssignment>& foliage,
                                   const std::vector<std::string>& sets,
                                   const TradeoffOutputs& out);

}  // namespace sylva::cli
